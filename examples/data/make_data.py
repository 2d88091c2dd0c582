"""Regenerate the gallery's example data from the `vega_datasets` package (pip install vega_datasets pandas pyarrow).

The files in this folder are committed; this script only documents and repeats how they were made.
Sources (as shipped by vega_datasets, BSD-3-Clause): Fisher's iris (1936), the StatLib "cars" data,
monthly stock prices 2000-2010, and Seattle daily weather (NOAA) 2012-2015.
"""
import json
import pathlib

import pandas as pd
from vega_datasets import local_data

here = pathlib.Path(__file__).parent

iris = local_data.iris()
iris.columns = ["sepal_length", "sepal_width", "petal_length", "petal_width", "species"]
iris.to_csv(here / "iris.csv", index=False)

# cars keeps its missing values (null mpg/horsepower): the gallery shows the drop warning.
cars = json.loads(pathlib.Path(local_data.cars.filepath).read_text())
for car in cars:
    car["Year"] = int(car["Year"][:4])
(here / "cars.json").write_text(json.dumps(cars, indent=1))

stocks = local_data.stocks()
stocks["date"] = stocks["date"].dt.strftime("%Y-%m-%d")
stocks.to_parquet(here / "stocks.parquet", index=False)

weather = local_data.seattle_weather()
weather = weather[weather["date"].dt.year == 2015].copy()
weather["date"] = weather["date"].dt.strftime("%Y-%m-%d")
weather.to_csv(here / "seattle-2015.csv", index=False)

# The 1982 models with complete records, for the Chernoff faces (a face per car stays legible).
cars82 = pd.DataFrame(cars)
cars82 = cars82[(cars82["Year"] == 1982)].dropna().head(40)
cars82.to_csv(here / "cars-1982.csv", index=False)
