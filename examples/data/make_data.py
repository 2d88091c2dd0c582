"""Regenerate the gallery's example data from the `vega_datasets` package (pip install vega_datasets pandas pyarrow).

The files in this folder are committed; this script only documents and repeats how they were made.
Sources (as shipped by vega_datasets, BSD-3-Clause): Fisher's iris (1936), the StatLib "cars" data,
monthly stock prices 2000-2010, and Seattle daily weather (NOAA) 2012-2015.
"""
import json
import pathlib

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

# Seattle's weather as shipped; the gallery picks the year 2015 and the monthly means with
# transforms in the spec, and the 1982 cars for the Chernoff faces from cars.json the same way.
weather = local_data.seattle_weather()
weather["date"] = weather["date"].dt.strftime("%Y-%m-%d")
weather.to_csv(here / "seattle-weather.csv", index=False)
