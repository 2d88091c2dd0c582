//! Transforms: a data source's `transform = [ ... ]` steps compiled onto its polars lazy plan.
//!
//! Each step is checked against the schema the previous steps leave (columns exist, types fit
//! the operators and functions), so problems are found before any data is read and point at
//! their place in the spec: the step's key, or the exact part of an expression. Steps then become
//! lazy operations, so polars pushes projections and predicates down into the file scan.
//!
//! The expression language is in [`expr`] (syntax) and [`lower`] (types and polars
//! expressions); aggregate and window calls in [`aggregate`] and [`window`]; nice bins in [`bin`];
//! the plans of a spec's sources, derived sources and their order in [`plan`].

pub mod aggregate;
pub mod bin;
pub mod expr;
pub mod lower;
pub mod place;
pub mod plan;
mod sql_files;
mod steps;
pub mod window;

use std::ops::Range;

use crate::spec::PathSeg;

pub use place::to_diagnostic;
pub use plan::{MissingScan, PlanError, SourcePlans, build_plans, collect_retrying};

/// A problem with a transform step, placed in the spec.
#[derive(Clone, Debug, PartialEq)]
pub struct TransformError {
    /// The spec path of the key or value at fault (`data.cars.transform[1].filter`).
    pub path: Vec<PathSeg>,
    /// For an expression: the byte range inside the expression text.
    pub inner: Option<Range<usize>>,
    /// What is wrong.
    pub message: String,
    /// How to fix it (may be empty).
    pub hint: String,
    /// Point at the key rather than the value.
    pub at_key: bool,
}

impl TransformError {
    /// An error at the value of `path`.
    pub fn at(path: Vec<PathSeg>, message: impl Into<String>) -> Self {
        Self { path, inner: None, message: message.into(), hint: String::new(), at_key: false }
    }

    /// With a hint.
    pub fn with_hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = hint.into();
        self
    }

    /// Pointing at the key of `path`.
    pub fn on_key(mut self) -> Self {
        self.at_key = true;
        self
    }
}

/// The first line of a (polars) message, bounded by [`crate::excerpt::message`]: polars quotes
/// offending values, and a long one must not flood the terminal.
pub fn first_line(text: &str) -> String {
    crate::excerpt::message(text.lines().next().unwrap_or("").trim()).into_owned()
}
