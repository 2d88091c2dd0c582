//! A `sql` step may query only the tables it is given: polars' SQL also has table functions
//! (`read_csv('...')`, `read_parquet`, `read_ipc`, `read_json`) that open any path, past the path
//! policy every data source goes through. They are found by parsing the query as polars does
//! (sqlparser's generic dialect, trailing commas allowed) and refused before it runs.

use std::ops::ControlFlow;

use sqlparser::ast::{TableFactor, Visit, Visitor};
use sqlparser::dialect::GenericDialect;
use sqlparser::parser::{Parser, ParserOptions};

/// The first table function `query` calls (`FROM name(args)`), if any. A query that does not
/// parse has none here (polars then reports its syntax error itself).
pub fn table_function(query: &str) -> Option<String> {
    let parser =
        Parser::new(&GenericDialect).with_options(ParserOptions { trailing_commas: true, ..Default::default() });
    let statements = parser.try_with_sql(query).ok()?.parse_statements().ok()?;
    let mut finder = Finder(None);
    let _ = statements.visit(&mut finder);
    finder.0
}

struct Finder(Option<String>);

impl Visitor for Finder {
    type Break = ();

    fn pre_visit_table_factor(&mut self, table: &TableFactor) -> ControlFlow<()> {
        match table {
            TableFactor::Table { name, args: Some(_), .. } => {
                self.0 = Some(name.to_string());
                ControlFlow::Break(())
            }
            TableFactor::Function { name, .. } => {
                self.0 = Some(name.to_string());
                ControlFlow::Break(())
            }
            _ => ControlFlow::Continue(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::table_function;

    #[test]
    fn table_functions_are_found_wherever_the_query_reads_a_table() {
        for query in [
            "SELECT * FROM read_csv('/etc/passwd')",
            "select * from READ_PARQUET('x.parquet')",
            "SELECT a FROM source JOIN read_ipc('y.arrow') AS r ON source.a = r.a",
            "SELECT * FROM (SELECT * FROM read_json('z.json')) AS t",
            "WITH t AS (SELECT * FROM read_csv('a.csv')) SELECT * FROM t",
            "SELECT * FROM source WHERE a IN (SELECT a FROM read_csv('a.csv'))",
            "SELECT * FROM read_csv /* hidden */ ('a.csv')",
            "SELECT * FROM \"read_csv\"('a.csv')",
        ] {
            assert!(table_function(query).is_some(), "{query}");
        }
        for query in
            ["SELECT * FROM source", "SELECT a, count(*) FROM source GROUP BY a", "SELECT read_csv FROM source"]
        {
            assert_eq!(table_function(query), None, "{query}");
        }
    }
}
