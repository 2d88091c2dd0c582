"""Make `grid-load.parquet`: a year (2023) of hourly readings of a regional power grid, synthetic
but shaped like the real thing (pip install numpy pandas pyarrow).

Demand follows the day (morning and evening peaks), the week (quieter weekends) and the seasons
(winter heating, summer cooling); solar output follows daylight and cloud; wind drifts over days;
price follows demand net of wind and solar. Used by the circle-segments example.
"""
import pathlib

import numpy as np
import pandas as pd

rng = np.random.default_rng(1982)
hours = pd.date_range("2023-01-01", periods=365 * 24, freq="h")
h = hours.hour.to_numpy()
doy = hours.day_of_year.to_numpy()
weekend = (hours.day_of_week.to_numpy() >= 5).astype(float)

season = np.cos(2 * np.pi * (doy - 15) / 365)  # +1 mid-January, -1 mid-July
temperature = 11 - 9 * season + 4 * np.sin(2 * np.pi * (h - 9) / 24) + rng.normal(0, 1.5, h.size)
daily = 0.55 + 0.25 * np.exp(-((h - 8) ** 2) / 6) + 0.35 * np.exp(-((h - 19) ** 2) / 8) - 0.3 * (h < 6)
heating_cooling = 0.6 * np.clip(12 - temperature, 0, None) / 12 + 0.4 * np.clip(temperature - 22, 0, None) / 10
demand = 900 * (daily + heating_cooling) * (1 - 0.12 * weekend) + rng.normal(0, 25, h.size)

daylight = np.clip(np.sin(np.pi * (h - 12 + 6 + 2 * -season) / (12 + 4 * -season)), 0, None)
cloud = np.clip(np.convolve(rng.normal(0.5, 0.35, h.size), np.ones(36) / 36, mode="same"), 0, 1)
solar = 420 * daylight * (0.45 + 0.55 * (1 - season) / 2) * (1 - 0.7 * cloud)

wind = np.clip(np.convolve(rng.gamma(2.0, 90, h.size), np.ones(60) / 60, mode="same") * (1.2 + 0.4 * season), 0, None)
residual = demand - solar - wind
price = 35 + 0.09 * np.clip(residual, 0, None) + rng.normal(0, 4, h.size)

table = pd.DataFrame(
    {
        "time": hours.strftime("%Y-%m-%dT%H:00:00"),
        "demand_mw": demand.round(1),
        "solar_mw": solar.round(1),
        "wind_mw": wind.round(1),
        "temperature_c": temperature.round(2),
        "price_eur_mwh": price.round(2),
    }
)
table.to_parquet(pathlib.Path(__file__).parent / "grid-load.parquet", index=False)
