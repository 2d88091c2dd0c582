//! One lazy plan per data source that needs one: the file scan (or the rows of another source,
//! for `from`), then the source's transform steps, built in dependency order.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use polars::prelude::*;

use super::TransformError;
use super::steps::{Env, apply_steps};
use crate::data::load::{LoadError, infer_format};
use crate::data::paths::{PathPolicy, resolve_data_path};
use crate::spec::{DataFormat, DataSource, PathSeg, SpannedValue, SpecDoc};

/// Why a source's plan could not be made.
#[derive(Debug)]
pub enum PlanError {
    /// Its file (or inline values) could not be read.
    Load {
        /// The data source.
        source: String,
        /// Why.
        error: LoadError,
    },
    /// A transform step, or `from`, is wrong.
    Transform(TransformError),
}

/// The plans of a spec's sources, and every problem met making them.
#[derive(Default)]
pub struct SourcePlans {
    /// The lazy plan of each source that has transforms, derives from another, or is derived from
    /// or joined by another.
    pub frames: BTreeMap<String, LazyFrame>,
    /// Problems, one source's first problem each (plus every misplaced option of its steps).
    pub errors: Vec<PlanError>,
    /// The sources that needed a plan and have none because of a problem.
    pub failed: BTreeSet<String>,
    /// The sources whose plan reads a file without comparing cells with the missing texts
    /// ([`MissingScan::Fast`]), itself or through a source it draws from.
    pub unlisted: BTreeSet<String>,
}

/// How a lazy CSV scan without the source's own `null_values` treats the default missing texts.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum MissingScan {
    /// The schema is inferred with the list; a file whose inferred columns are numbers and dates
    /// only is then read without comparing each cell with the list (reused schema, no second
    /// inference). A missing text below the inferred rows makes the collect fail: build the
    /// plans again with [`MissingScan::Listed`] ([`collect_retrying`]).
    Fast,
    /// Every cell is compared with the list.
    Listed,
}

impl std::fmt::Debug for SourcePlans {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SourcePlans")
            .field("frames", &self.frames.keys().collect::<Vec<_>>())
            .field("errors", &self.errors)
            .field("failed", &self.failed)
            .field("unlisted", &self.unlisted)
            .finish()
    }
}

/// Whether a source needs a lazy plan: it transforms or derives, or others build on it.
fn needs_plan(name: &str, source: &DataSource, referenced: &BTreeSet<String>) -> bool {
    source.transform.as_ref().is_some_and(|t| !t.is_empty()) || source.from.is_some() || referenced.contains(name)
}

/// The other sources a source builds on: `from`, and the targets of its `join`/`lookup` steps.
pub fn dependencies(source: &DataSource) -> Vec<String> {
    let mut out: Vec<String> = source.from.iter().cloned().collect();
    for step in source.transform.iter().flatten() {
        out.extend(step.join.iter().chain(step.lookup.iter()).cloned());
    }
    out
}

/// Build the plans of every source that needs one (or of all sources, with `all`).
pub fn build_plans(
    sources: &BTreeMap<String, DataSource>,
    doc: &SpecDoc,
    spec_dir: &Path,
    policy: PathPolicy,
    all: bool,
    missing: MissingScan,
) -> SourcePlans {
    let referenced: BTreeSet<String> = sources.values().flat_map(dependencies).collect();
    let names: Vec<String> = sources.keys().cloned().collect();
    let mut plans = SourcePlans::default();
    let mut state: BTreeMap<&str, Visit> = BTreeMap::new();
    for name in sources.keys() {
        if all || needs_plan(name, &sources[name], &referenced) {
            let mut stack = Vec::new();
            let place = Place { sources, doc, spec_dir, policy, missing, names: &names };
            visit(name, &place, &mut state, &mut stack, &mut plans);
        }
    }
    plans
}

/// Run `work` on the plan of `name` in `plans`; when it fails and the plan skipped the missing
/// texts, run it again on the [`MissingScan::Listed`] plans, which `listed` builds (once:
/// they are kept in `cache`). `None` when no plan of `name` exists.
pub fn collect_retrying<T, E>(
    plans: &SourcePlans,
    cache: &mut Option<SourcePlans>,
    listed: impl FnOnce() -> SourcePlans,
    name: &str,
    work: impl Fn(&LazyFrame) -> Result<T, E>,
) -> Option<Result<T, E>> {
    let first = work(plans.frames.get(name)?);
    if first.is_ok() || !plans.unlisted.contains(name) {
        return Some(first);
    }
    let again = cache.get_or_insert_with(listed);
    Some(again.frames.get(name).map_or(first, work))
}

/// What every source's plan is made against.
struct Place<'a> {
    sources: &'a BTreeMap<String, DataSource>,
    doc: &'a SpecDoc,
    spec_dir: &'a Path,
    policy: PathPolicy,
    missing: MissingScan,
    names: &'a [String],
}

#[derive(Clone, Copy, PartialEq)]
enum Visit {
    Active,
    Done,
}

fn visit<'a>(
    name: &'a str,
    place: &Place<'a>,
    state: &mut BTreeMap<&'a str, Visit>,
    stack: &mut Vec<&'a str>,
    plans: &mut SourcePlans,
) {
    let sources = place.sources;
    let Some(source) = sources.get(name) else { return };
    match state.get(name) {
        Some(Visit::Done) => return,
        Some(Visit::Active) => {
            let start = stack.iter().position(|s| *s == name).unwrap_or(0);
            let mut cycle: Vec<&str> = stack[start..].to_vec();
            cycle.push(name);
            let path = source_path(name, if source.from.is_some() { "from" } else { "transform" });
            plans.errors.push(PlanError::Transform(
                TransformError::at(path, format!("data sources build on each other in a cycle: {}", cycle.join(" → ")))
                    .with_hint("a source may start from or join only sources that do not lead back to it"),
            ));
            plans.failed.insert(name.to_owned());
            return;
        }
        None => {}
    }
    state.insert(name, Visit::Active);
    stack.push(name);
    for dep in dependencies(source) {
        if let Some((key, _)) = sources.get_key_value(dep.as_str()) {
            visit(key, place, state, stack, plans);
        }
    }
    stack.pop();
    state.insert(name, Visit::Done);
    if dependencies(source).iter().any(|dep| plans.unlisted.contains(dep)) {
        plans.unlisted.insert(name.to_owned());
    }
    match plan_one(name, source, place, plans) {
        Some(frame) => {
            plans.frames.insert(name.to_owned(), frame);
        }
        None => {
            plans.failed.insert(name.to_owned());
        }
    }
}

fn plan_one(name: &str, source: &DataSource, place: &Place, plans: &mut SourcePlans) -> Option<LazyFrame> {
    let names = place.names;
    let base = match &source.from {
        Some(from) => match plans.frames.get(from) {
            Some(frame) => frame.clone(),
            None => {
                let known: Vec<&str> = names.iter().map(String::as_str).filter(|n| *n != name).collect();
                // A source that failed to load has its own error already.
                if !names.iter().any(|n| n == from) {
                    plans.errors.push(PlanError::Transform(
                        TransformError::at(
                            source_path(name, "from"),
                            format!("no data source \"{from}\" to start from"),
                        )
                        .with_hint(crate::spec::suggest::hint(
                            from,
                            &known,
                            "data sources",
                            true,
                        )),
                    ));
                }
                return None;
            }
        },
        None => match scan(source, place.spec_dir, place.policy, place.missing) {
            Ok(Scanned { frame, unlisted }) => {
                if unlisted {
                    plans.unlisted.insert(name.to_owned());
                }
                frame
            }
            Err(error) => {
                plans.errors.push(PlanError::Load { source: name.to_owned(), error });
                return None;
            }
        },
    };
    let steps = place.doc.get(&source_path(name, "transform"));
    let Some(items) = steps.and_then(SpannedValue::as_array) else { return Some(base) };
    let env = Env { source: name, others: &plans.frames, names };
    match apply_steps(base, items, &source_path(name, "transform"), &env) {
        Ok(frame) => Some(frame),
        Err(errors) => {
            plans.errors.extend(errors.into_iter().map(PlanError::Transform));
            None
        }
    }
}

/// The spec path `data.NAME.KEY`.
pub fn source_path(name: &str, key: &str) -> Vec<PathSeg> {
    vec![PathSeg::Key("data".into()), PathSeg::Key(name.to_owned()), PathSeg::Key(key.to_owned())]
}

/// A source's rows as a lazy frame, and whether its cells skip the missing texts.
struct Scanned {
    frame: LazyFrame,
    unlisted: bool,
}

/// The rows of a source as a lazy frame: plain CSV and Parquet files without `parse` rules are
/// scanned lazily (so the transforms' projections and predicates reach the reader); other
/// sources are read whole by their readers.
fn scan(source: &DataSource, spec_dir: &Path, policy: PathPolicy, missing: MissingScan) -> Result<Scanned, LoadError> {
    if let (Some(path), None) = (&source.path, &source.parse) {
        let resolved = resolve_data_path(spec_dir, path, policy).map_err(LoadError::Path)?;
        let ext = resolved.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).unwrap_or_default();
        let format = source.format.or_else(|| infer_format(&resolved));
        // Empty, missing and compressed files go to the readers, which say what is wrong.
        let readable = std::fs::metadata(&resolved).is_ok_and(|m| m.is_file() && m.len() > 0);
        let text = resolved.to_string_lossy().into_owned();
        let separator = source.delimiter.as_deref().and_then(|d| d.bytes().next()).unwrap_or(if ext == "tsv" {
            b'\t'
        } else {
            b','
        });
        let csv_scan = |null_values: Option<NullValues>, schema: Option<SchemaRef>| {
            LazyCsvReader::new(PlRefPath::new(text.as_str()))
                .with_schema(schema)
                .with_has_header(true)
                .with_infer_schema_length(Some(10_000))
                .with_try_parse_dates(true)
                .with_null_values(null_values)
                .map_parse_options(|p| p.with_separator(separator))
                .finish()
        };
        let is_csv = matches!(format, Some(DataFormat::Csv)) && matches!(ext.as_str(), "csv" | "tsv" | "txt");
        let default_missing = is_csv && source.null_values.is_none();
        if readable && is_csv {
            let tail = crate::data::csv_tail::check_file(&resolved, separator)
                .map_err(|e| LoadError::from_io(&resolved, e))?;
            tail.map_err(|message| LoadError::Parse {
                origin: format!("`{}`", resolved.display()),
                format: DataFormat::Csv,
                message: message.into(),
            })?;
        }
        let lazy = match format {
            Some(DataFormat::Csv) if readable && is_csv => {
                Some(csv_scan(crate::data::missing::csv_null_values(source.null_values.as_deref()), None))
            }
            Some(DataFormat::Parquet) if readable && matches!(ext.as_str(), "parquet" | "pq") => {
                let mut file =
                    crate::data::regular_file::open(&resolved).map_err(|e| LoadError::from_io(&resolved, e))?;
                crate::data::contained::contain(|| crate::data::parquet_bounds::check(&mut file))
                    .and_then(|checked| checked)
                    .map_err(|message| LoadError::Parse {
                        origin: format!("`{}`", resolved.display()),
                        format: DataFormat::Parquet,
                        message,
                    })?;
                Some(LazyFrame::scan_parquet(PlRefPath::new(text.as_str()), ScanArgsParquet::default()))
            }
            _ => None,
        };
        if let (Some(lf), Some(format)) = (lazy, format) {
            let origin = format!("`{}`", resolved.display());
            let failed = |e: PolarsError| LoadError::Parse {
                origin: origin.clone(),
                format,
                message: super::first_line(&e.to_string()),
            };
            let mut lf = lf.map_err(failed)?;
            // Check the file now (header, schema), so a bad file is a load error, not a step's.
            let schema_of = |lf: &mut LazyFrame| {
                crate::data::contained::contain(|| lf.collect_schema())
                    .map_err(|message| LoadError::Parse { origin: origin.clone(), format, message })?
                    .map_err(failed)
            };
            let schema = schema_of(&mut lf)?;
            // Numbers and dates only: the cells need not be compared with the missing texts.
            let unlisted = default_missing
                && missing == MissingScan::Fast
                && !crate::data::missing::may_hold_missing_text(&schema);
            if unlisted {
                lf = csv_scan(None, Some(schema.clone())).map_err(failed)?;
            }
            // A byte-order mark is not part of the first column's name.
            if let Some(first) = schema.iter_names().next()
                && let Some(clean) = first.strip_prefix('\u{feff}')
            {
                lf = lf.rename([first.as_str()], [clean], true);
            }
            return Ok(Scanned { frame: lf, unlisted });
        }
    }
    let frame = crate::data::load::source_frame(source, spec_dir, policy)?.lazy();
    Ok(Scanned { frame, unlisted: false })
}
