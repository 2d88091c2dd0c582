"""Write tests/fixtures/pyarrow_pages.parquet: a Parquet file from another writer than polars, with
the layouts the page-header checks must accept (dictionary pages, data pages V2, small pages, many
row groups, zstd, nulls, a nested list column).

Usage: python3 scripts/parquet_fixture.py   (needs pyarrow: pip install pyarrow)
"""

import pyarrow as pa
import pyarrow.parquet as pq

N = 3000
table = pa.table(
    {
        "x": [i / 10 if i % 7 else None for i in range(N)],
        "cat": [["alpha", "beta", "gamma"][i % 3] for i in range(N)],
        "l": [[i, i + 1] if i % 5 else None for i in range(N)],
    }
)
pq.write_table(
    table,
    "tests/fixtures/pyarrow_pages.parquet",
    data_page_version="2.0",
    data_page_size=512,
    row_group_size=1000,
    compression="zstd",
)
