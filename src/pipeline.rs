//! The whole pipeline for one spec file: check the spec, load its data, check the columns, draw
//! every chart (in parallel) and write the requested outputs.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde_json::Value;

use crate::data::transform::MissingScan;
use crate::data::{self, PathPolicy, Table};
use crate::lint::{self, ChartLint};
use crate::mark::{self, ChartOutput, MarkError};
use crate::output;
use crate::render;
use crate::selection::{self, Highlight};
use crate::spec::{self, Diagnostic, PathSeg, SourceFile, Spec, SpecDoc};
use crate::timing::timed;

/// A spec whose every check passed: ready to draw.
#[derive(Debug)]
pub struct Loaded {
    /// The spec file's text, for rendering diagnostics.
    pub source: SourceFile,
    /// The typed spec, with each categorical colour encoding that names no `domain` given its
    /// column's spec-wide category order ([`mark::categorical::share_domains`]), so a category
    /// has the same colour in every chart.
    pub spec: Spec,
    /// Positions of everything in the spec.
    pub doc: SpecDoc,
    /// Loaded tables by data source name.
    pub tables: BTreeMap<String, Table>,
    /// Loaded volumes by data source name (NIfTI files, 3-D `.npy` arrays, raw volumes); a
    /// volume source has no table.
    pub volumes: BTreeMap<String, data::volume::Volume>,
    /// Every selection, evaluated once against its data source (shared by the charts naming it).
    pub highlights: BTreeMap<String, Highlight>,
    /// The keys each chart (by name) left out and took from a column of the conventional name
    /// ([`spec::defaults`]).
    pub defaults: BTreeMap<String, Vec<spec::defaults::Taken>>,
    /// Warnings found while loading (printed, not fatal).
    pub warnings: Vec<Diagnostic>,
    /// The sources whose rows stay in their lazy plans, by name: every chart of theirs only
    /// counts rows (density views), so the engine streams them through the counting and they are
    /// never held. Their tables have the columns and no rows.
    pub plans: BTreeMap<String, data::density::plan::PlanRows>,
}

/// The defaults taken by chart index, keyed by the charts' names instead.
fn chart_defaults(
    json: &Value,
    taken: BTreeMap<usize, Vec<spec::defaults::Taken>>,
) -> BTreeMap<String, Vec<spec::defaults::Taken>> {
    let charts = json.get("chart").and_then(Value::as_array);
    let name = |i: usize| charts?.get(i)?.get("name")?.as_str().map(str::to_owned);
    taken.into_iter().filter_map(|(i, t)| Some((name(i)?, t))).collect()
}

/// A spec that failed its checks: every problem found, with the text to render them against.
#[derive(Debug)]
pub struct Failed {
    /// The spec file's text (empty if it could not be read).
    pub source: SourceFile,
    /// Every problem, errors and warnings.
    pub diagnostics: Vec<Diagnostic>,
}

impl Failed {
    /// All diagnostics rendered for a terminal.
    pub fn render(&self) -> String {
        crate::spec::render_all(&self.source, &self.diagnostics)
    }
}

/// Read a spec file, validate it, load its data and check every column reference, reporting all
/// problems at once.
pub fn load(spec_path: &Path, policy: PathPolicy) -> Result<Loaded, Failed> {
    let unread = |message: String, hint: &str| Failed {
        source: SourceFile { path: spec_path.to_path_buf(), text: String::new() },
        diagnostics: vec![Diagnostic::error(message).with_hint(hint)],
    };
    let bytes = crate::data::regular_file::read_capped(spec_path, crate::data::regular_file::MAX_SPEC_BYTES, "spec")
        .map_err(|e| {
            unread(
                format!("cannot read spec file `{}`: {e}", spec_path.display()),
                "check the path; specs are TOML files such as examples/gallery.toml",
            )
        })?;
    let text = String::from_utf8(bytes).map_err(|_| {
        unread(format!("spec file `{}` is not UTF-8 text", spec_path.display()), "save the spec as UTF-8")
    })?;
    let source = SourceFile { path: spec_path.to_path_buf(), text };
    let spec_dir = spec_path.parent().map(Path::to_path_buf).unwrap_or_else(|| PathBuf::from("."));
    load_source(source, &spec_dir, policy)
}

/// [`load`] for a spec already read: its data paths resolve against `spec_dir`.
pub fn load_source(source: SourceFile, spec_dir: &Path, policy: PathPolicy) -> Result<Loaded, Failed> {
    let (checked, deferred) = spec::check_deferring(&source);
    // Problems with the spec itself, replaced when it is checked again with its defaults filled.
    let mut spec_problems = checked.diagnostics;
    let mut diagnostics = Vec::new();
    let Some(mut doc) = checked.doc else {
        return Err(Failed { source, diagnostics: spec_problems });
    };
    let mut json = doc.to_json();
    let spec_dir = spec_dir.to_path_buf();

    // Load every data source that is itself valid, even if other parts of the spec are not, so
    // that column names can be checked in the same run.
    let sources: BTreeMap<String, spec::DataSource> = match &checked.spec {
        Some(s) => s.data.clone(),
        None => valid_sources(&json),
    };
    let (volumes, sources) = load_volumes(sources, &doc, &spec_dir, policy, |_| true, &mut diagnostics);
    let (on_engines, sources) = split_engine_sources(sources, &doc, &mut diagnostics);
    let needed = needed_columns(&json);
    let conventional = conventional_columns(&json);
    let mut tables = BTreeMap::new();
    let build = |missing| data::transform::build_plans(&sources, &doc, &spec_dir, policy, false, missing);
    let build_every = |missing| data::transform::build_plans(&sources, &doc, &spec_dir, policy, true, missing);
    let plans = timed("plan data", || build(MissingScan::Fast));
    let mut listed = None;
    diagnostics.extend(plans.errors.iter().map(|e| data::transform::to_diagnostic(e, &doc, &source.text)));
    let counted = counted_only(&json, Counting::InProcess);
    let counted_on_engine = counted_only(&json, Counting::OnEngine);
    let mut every_plan = None;
    let mut kept_in_plans = BTreeMap::new();
    for (name, source_spec) in &on_engines {
        let source_key = |key: &str| {
            doc.span_of(&[PathSeg::Key("data".into()), PathSeg::Key(name.clone()), PathSeg::Key(key.into())])
        };
        let query = match data::engine::source::query_of(source_spec, name, &spec_dir) {
            Ok(query) => query,
            Err((key, message)) => {
                diagnostics.push(Diagnostic::error(format!("data \"{name}\": {message}")).at_opt(source_key(key)));
                continue;
            }
        };
        let wanted: Option<Vec<String>> = needed.get(name).map(|set| set.iter().cloned().collect());
        let whole = conventional.get(name).is_some_and(|set| !set.is_empty());
        let loaded = timed(&format!("engine data \"{name}\""), || {
            load_from_engine(
                query,
                name,
                counted_on_engine.contains(name),
                if whole { None } else { wanted.as_deref() },
                &json,
            )
        });
        match loaded {
            Ok((table, plan)) => {
                tables.insert(name.clone(), table);
                if let Some(plan) = plan {
                    kept_in_plans.insert(name.clone(), plan);
                }
            }
            Err(message) => diagnostics.push(Diagnostic::error(message).at_opt(source_key("engine"))),
        }
    }
    for (name, source_spec) in &sources {
        if counted.contains(name) && !plans.failed.contains(name) {
            let every = every_plan.get_or_insert_with(|| build_every(MissingScan::Listed));
            // Every source has a plan once `all` is asked for; one that cannot be planned is read
            // as usual, which reports why.
            let every = &*every;
            if let Some(frame) = every.frames.get(name) {
                let parquet = plain_parquet(source_spec, &spec_dir);
                match timed(&format!("plan rows \"{name}\""), || keep_in_plan(frame, name, parquet, &json)) {
                    Ok(Some((table, plan))) => {
                        tables.insert(name.clone(), table);
                        kept_in_plans.insert(name.clone(), plan);
                        continue;
                    }
                    Ok(None) => {}
                    Err(message) => {
                        let at = doc.span_of(&[PathSeg::Key("data".into()), PathSeg::Key(name.clone())]);
                        diagnostics.push(Diagnostic::error(message).at_opt(at));
                        continue;
                    }
                }
            }
        }
        let wanted: Option<Vec<String>> = needed.get(name).map(|set| set.iter().cloned().collect());
        let maybe: Vec<String> = conventional.get(name).map(|set| set.iter().cloned().collect()).unwrap_or_default();
        if plans.failed.contains(name) {
            continue;
        }
        let collected = timed(&format!("load data \"{name}\""), || {
            let listed_plans = || build(MissingScan::Listed);
            data::transform::collect_retrying(&plans, &mut listed, listed_plans, name, |frame| {
                collect_source(frame, wanted.as_deref(), &maybe, name)
            })
        });
        if let Some(collected) = collected {
            match collected {
                Ok(table) => {
                    let rules = source_spec.parse.as_ref();
                    let at = doc.span_of(&data::transform::plan::source_path(name, "transform"));
                    for warning in data::date_guess::date_warnings(&table, |c| rules.is_none_or(|r| !r.contains_key(c)))
                    {
                        diagnostics.push(Diagnostic::warning(format!("data \"{name}\": {warning}")).at_opt(at.clone()));
                    }
                    tables.insert(name.clone(), table);
                }
                Err(message) => {
                    let key = if source_spec.transform.is_some() { "transform" } else { "from" };
                    let path = data::transform::plan::source_path(name, key);
                    diagnostics.push(
                        Diagnostic::error(format!("data \"{name}\": {message}"))
                            .with_hint("`dataink data SPEC NAME` shows the rows after each source's transforms")
                            .at_opt(doc.span_of(&path)),
                    );
                }
            }
            continue;
        }
        let key = if source_spec.path.is_some() { "path" } else { "values" };
        let at = doc.span_of(&[PathSeg::Key("data".into()), PathSeg::Key(name.clone()), PathSeg::Key(key.into())]);
        match timed(&format!("load data \"{name}\""), || {
            // A file reader cannot tell which of the conventional columns exist before reading:
            // asking for one that does not fails the read, and the file is read again whole. A
            // source with charts taking defaults is read whole at once instead.
            let columns = if maybe.is_empty() { wanted.as_deref() } else { None };
            data::load_source_with_warnings(source_spec, &spec_dir, policy, columns)
        }) {
            Ok(loaded) => {
                for warning in loaded.warnings {
                    diagnostics.push(Diagnostic::warning(format!("data \"{name}\": {warning}")).at_opt(at.clone()));
                }
                tables.insert(name.clone(), loaded.table);
            }
            Err(e) => {
                diagnostics.push(Diagnostic::error(format!("data \"{name}\": {e}")).with_hint(e.hint()).at_opt(at));
            }
        }
    }
    let mut typed = checked.spec;
    let mut defaults = BTreeMap::new();
    if deferred {
        let filled = spec::defaults::fill(&mut doc, |name| {
            tables.get(name).map(|t| t.column_names().into_iter().map(str::to_owned).collect())
        });
        let rechecked = spec::check_filled(doc, &filled);
        spec_problems = rechecked.diagnostics;
        typed = rechecked.spec;
        doc = rechecked.doc.expect("a filled spec keeps its document");
        json = doc.to_json();
        defaults = chart_defaults(&json, filled.taken);
    }
    diagnostics.splice(0..0, spec_problems);
    diagnostics.extend(check_columns(&json, &doc, &tables));
    let (highlights, selection_errors) = evaluate_selections(typed.as_ref(), &doc, &tables);
    diagnostics.extend(selection_errors);
    if let Some(spec) = &typed {
        diagnostics.extend(check_lint_config(spec, &doc));
    }

    let has_errors = diagnostics.iter().any(Diagnostic::is_error);
    match typed {
        Some(mut spec) if !has_errors => {
            mark::categorical::share_domains(&mut spec.chart, &tables);
            Ok(Loaded {
                source,
                spec,
                doc,
                tables,
                volumes,
                highlights,
                defaults,
                warnings: diagnostics,
                plans: kept_in_plans,
            })
        }
        _ => Err(Failed { source, diagnostics }),
    }
}

/// Where a source's rows would be counted.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Counting {
    /// In this process, by scans of its lazy plan.
    InProcess,
    /// On its engine.
    OnEngine,
}

/// The sources whose rows no chart needs one by one: each of their charts is of a kind that
/// can count its rows there, with none of the keys that make it need them (the registry's
/// [`mark::registry::RowCounting`]: density scatters; in-process histograms of one group, bar
/// charts and heatmaps); and no selection reads them.
fn counted_only(json: &Value, counting: Counting) -> BTreeSet<String> {
    let selected: BTreeSet<&str> = json
        .get("selection")
        .and_then(Value::as_object)
        .into_iter()
        .flat_map(|m| m.values().filter_map(|s| s.get("data").and_then(Value::as_str)))
        .collect();
    let mut verdicts: BTreeMap<String, bool> = BTreeMap::new();
    for chart in json.get("chart").and_then(Value::as_array).into_iter().flatten() {
        let Some(data) = chart.get("data").and_then(Value::as_str) else { continue };
        let counts = chart
            .get("kind")
            .and_then(Value::as_str)
            .and_then(mark::registry::kind_info)
            .and_then(|info| info.counts_rows)
            .is_some_and(|rule| rule.counts(chart, counting == Counting::OnEngine));
        *verdicts.entry(data.to_string()).or_insert(true) &= counts;
    }
    verdicts.into_iter().filter(|(name, counts)| *counts && !selected.contains(name.as_str())).map(|(n, _)| n).collect()
}

/// Keep the rows of source `name` in its plan `frame` when every chart of it will draw them as a
/// density at the plan's row count: the source's table (columns, no rows) and the plan; `None`
/// when some chart would draw points (few rows under `mode = "auto"`).
fn keep_in_plan(
    frame: &polars::prelude::LazyFrame,
    name: &str,
    parquet: Option<PathBuf>,
    json: &Value,
) -> Result<Option<(Table, data::density::plan::PlanRows)>, String> {
    let mut plan = data::density::plan::PlanRows::new(frame.clone(), name)?;
    if let Some(path) = parquet {
        plan = plan.scanning_only(path);
    }
    kept_if_only_counted(plan, name, json)
}

/// The sources that live on an engine, apart from the others; a source that starts from or
/// joins one of them is dropped with an error (its rows would have to come back whole).
fn split_engine_sources(
    sources: BTreeMap<String, spec::DataSource>,
    doc: &SpecDoc,
    diagnostics: &mut Vec<Diagnostic>,
) -> (BTreeMap<String, spec::DataSource>, BTreeMap<String, spec::DataSource>) {
    let (on_engines, local): (BTreeMap<_, _>, BTreeMap<_, _>) =
        sources.into_iter().partition(|(_, source)| source.engine.is_some());
    let mut kept = BTreeMap::new();
    for (name, source) in local {
        match data::transform::plan::dependencies(&source).into_iter().find(|d| on_engines.contains_key(d)) {
            Some(engine_source) => {
                let key = if source.from.is_some() { "from" } else { "transform" };
                diagnostics.push(
                    Diagnostic::error(format!(
                        "data \"{name}\" builds on \"{engine_source}\", which is on an engine; that is not supported yet"
                    ))
                    .with_hint(format!("write the step as a `sql` step of \"{engine_source}\" itself, so it runs on the engine"))
                    .at_opt(doc.span_of(&data::transform::plan::source_path(&name, key))),
                );
            }
            None => {
                kept.insert(name, source);
            }
        }
    }
    (on_engines, kept)
}

/// An engine source's table and, when every chart of it only counts its rows, the engine
/// query that counts them (`counted`: the source is one [`counted_only`] allows); otherwise its
/// rows (the columns `wanted`, all when `None`) fetched into the table.
fn load_from_engine(
    query: data::engine::EngineQuery,
    name: &str,
    counted: bool,
    wanted: Option<&[String]>,
    json: &Value,
) -> Result<(Table, Option<data::density::plan::PlanRows>), String> {
    if counted {
        let plan = data::density::plan::PlanRows::on_engine(query.clone(), name)?;
        if let Some((table, plan)) = kept_if_only_counted(plan, name, json)? {
            return Ok((table, Some(plan)));
        }
    }
    let frame = query.rows_of(wanted, data::engine::MAX_FETCHED_ROWS).map_err(|e| format!("data \"{name}\": {e}"))?;
    let table = data::load::frame_to_table(&frame, &format!("data \"{name}\""))
        .map_err(|e| format!("data \"{name}\": {e}; {}", e.hint()))?;
    Ok((table, None))
}

/// The plan kept, with the source's table (columns, no rows), when every chart of source `name`
/// only counts rows at the plan's row count (a density scatter, or a histogram, bar chart or
/// heatmap of more rows than [`mark::density::AUTO_DENSITY_ROWS`]); `None` when some chart would
/// draw points, or bin or group rows it holds.
fn kept_if_only_counted(
    plan: data::density::plan::PlanRows,
    name: &str,
    json: &Value,
) -> Result<Option<(Table, data::density::plan::PlanRows)>, String> {
    let rows = plan.rows();
    let charts = json.get("chart").and_then(Value::as_array).into_iter().flatten();
    let all_density = charts
        .filter(|c| c.get("data").and_then(Value::as_str) == Some(name))
        .all(|c| c.get("mode").and_then(Value::as_str) == Some("density") || rows > mark::density::AUTO_DENSITY_ROWS);
    if !all_density {
        return Ok(None);
    }
    let columns = plan.empty_frame()?;
    let table = data::load::frame_to_table(&columns, &format!("data \"{name}\""))
        .map_err(|e| format!("data \"{name}\": {e}; {}", e.hint()))?;
    Ok(Some((table, plan)))
}

/// The Parquet file a source reads as it is (no `from`, no transform steps), if it is one.
fn plain_parquet(source: &spec::DataSource, spec_dir: &Path) -> Option<PathBuf> {
    let path = spec_dir.join(source.path.as_deref()?);
    let format = source.format.or_else(|| data::load::infer_format(&path));
    let plain = source.from.is_none() && source.transform.as_ref().is_none_or(|t| t.is_empty());
    (plain && format == Some(spec::DataFormat::Parquet)).then_some(path)
}

/// Read the sources that are volumes, noting their warnings and errors in `diagnostics`; the
/// volumes by name, and the table sources left (without those that build on a volume, which get
/// an error: transforms read tables).
fn load_volumes(
    sources: BTreeMap<String, spec::DataSource>,
    doc: &SpecDoc,
    spec_dir: &Path,
    policy: PathPolicy,
    wanted: impl Fn(&str) -> bool,
    diagnostics: &mut Vec<Diagnostic>,
) -> (BTreeMap<String, data::volume::Volume>, BTreeMap<String, spec::DataSource>) {
    let mut volumes = BTreeMap::new();
    let mut tables = BTreeMap::new();
    let mut volume_names = Vec::new();
    for (name, source) in sources {
        let at = doc.span_of(&[PathSeg::Key("data".into()), PathSeg::Key(name.clone()), PathSeg::Key("path".into())]);
        let read = |source: &spec::DataSource| {
            if wanted(&name) {
                data::volume::source::load(source, spec_dir, policy).map(|r| r.map(Some))
            } else {
                data::volume::source::classify(source, spec_dir, policy).map(|r| r.map(|_| None))
            }
        };
        match timed(&format!("load volume \"{name}\""), || read(&source)) {
            None => {
                tables.insert(name, source);
                continue;
            }
            Some(Ok(None)) => {}
            Some(Ok(Some(read))) => {
                for warning in read.warnings {
                    diagnostics.push(Diagnostic::warning(format!("data \"{name}\": {warning}")).at_opt(at.clone()));
                }
                volumes.insert(name.clone(), read.volume);
            }
            Some(Err(e)) => {
                diagnostics.push(Diagnostic::error(format!("data \"{name}\": {e}")).with_hint(e.hint()).at_opt(at));
            }
        }
        volume_names.push(name);
    }
    tables.retain(|name, source| {
        let Some(volume) = data::transform::plan::dependencies(source).into_iter().find(|d| volume_names.contains(d))
        else {
            return true;
        };
        let at = doc.span_of(&[PathSeg::Key("data".into()), PathSeg::Key(name.clone())]);
        diagnostics.push(
            Diagnostic::error(format!(
                "data \"{name}\": data \"{volume}\" is a volume; `from`, `join` and `lookup` read tables"
            ))
            .with_hint("a volume is read by the volume chart kinds directly")
            .at_opt(at),
        );
        false
    });
    (volumes, tables)
}

/// A data source as its charts see it: the schema and first rows after its transforms.
#[derive(Debug)]
pub struct SourcePreview {
    /// The source's name.
    pub name: String,
    /// Column names and types.
    pub schema: Vec<(String, String)>,
    /// Rows after the transforms.
    pub rows: usize,
    /// The first rows, as a text table.
    pub head: String,
    /// For a volume: its description ([`data::volume::summary::describe`]) instead of rows.
    pub volume: Option<String>,
}

/// The sources of a spec (or only `only`) after their transforms, with the first `rows` rows.
/// Only the spec's `[data]` tables need to be valid: charts are not checked.
pub fn preview_sources(
    spec_path: &Path,
    policy: PathPolicy,
    only: Option<&str>,
    rows: usize,
) -> Result<Vec<SourcePreview>, Failed> {
    let fail = |source: SourceFile, diagnostics| Failed { source, diagnostics };
    let source = match SourceFile::read(spec_path) {
        Ok(s) => s,
        Err(e) => {
            let d = Diagnostic::error(format!("cannot read spec file `{}`: {e}", spec_path.display()));
            return Err(fail(SourceFile::new(spec_path, String::new()), vec![d]));
        }
    };
    let checked = spec::check(&source);
    let Some(doc) = checked.doc else { return Err(fail(source, checked.diagnostics)) };
    let sources = match &checked.spec {
        Some(s) => s.data.clone(),
        None => valid_sources(&doc.to_json()),
    };
    let data_errors: Vec<Diagnostic> = checked
        .diagnostics
        .into_iter()
        .filter(|d| d.is_error() && d.span.as_ref().is_some_and(|sp| in_data_table(&doc, sp.start)))
        .collect();
    if !data_errors.is_empty() {
        return Err(fail(source, data_errors));
    }
    if let Some(name) = only
        && !sources.contains_key(name)
    {
        let known: Vec<&str> = sources.keys().map(String::as_str).collect();
        let d = Diagnostic::error(format!("no data source \"{name}\" in the spec")).with_hint(spec::suggest::hint(
            name,
            &known,
            "data sources",
            true,
        ));
        return Err(fail(source, vec![d]));
    }
    let spec_dir = spec_path.parent().map(Path::to_path_buf).unwrap_or_else(|| PathBuf::from("."));
    let mut diagnostics = Vec::new();
    let mut out = Vec::new();
    let wanted = |name: &str| only.is_none_or(|o| o == name);
    let (volumes, sources) = load_volumes(sources, &doc, &spec_dir, policy, wanted, &mut diagnostics);
    for (name, volume) in volumes {
        let kind = format!("volume of {} × {} × {} voxels", volume.dims()[0], volume.dims()[1], volume.dims()[2]);
        let summary = data::volume::summary::describe(&volume);
        out.push(SourcePreview { name, schema: Vec::new(), rows: volume.len(), head: kind, volume: Some(summary) });
    }
    let (on_engines, sources) = split_engine_sources(sources, &doc, &mut diagnostics);
    for (name, source_spec) in on_engines.iter().filter(|(name, _)| wanted(name)) {
        let at = doc.span_of(&[PathSeg::Key("data".into()), PathSeg::Key(name.clone())]);
        match preview_on_engine(source_spec, name, &spec_dir, rows) {
            Ok(preview) => out.push(preview),
            Err(message) => diagnostics.push(Diagnostic::error(format!("data \"{name}\": {message}")).at_opt(at)),
        }
    }
    let build = |missing| data::transform::build_plans(&sources, &doc, &spec_dir, policy, true, missing);
    let plans = build(MissingScan::Fast);
    let mut listed = None;
    diagnostics.extend(plans.errors.iter().map(|e| data::transform::to_diagnostic(e, &doc, &source.text)));
    for name in plans.frames.keys() {
        if only.is_some_and(|o| o != name) {
            continue;
        }
        let preview = |frame: &polars::prelude::LazyFrame| {
            let mut lf = frame.clone();
            data::contained::contain(|| {
                lf.collect_schema().and_then(|schema| {
                    let count = frame.clone().select([polars::prelude::len()]).collect()?;
                    let n = count
                        .columns()
                        .first()
                        .and_then(|c| c.get(0).ok())
                        .and_then(|v| v.extract::<usize>())
                        .unwrap_or(0);
                    let head = frame.clone().limit(rows as polars::prelude::IdxSize).collect()?;
                    Ok((schema, n, head))
                })
            })
            .and_then(|r| r.map_err(|e| data::transform::first_line(&e.to_string())))
        };
        let listed_plans = || build(MissingScan::Listed);
        let Some(result) = data::transform::collect_retrying(&plans, &mut listed, listed_plans, name, preview) else {
            continue;
        };
        match result {
            Ok((schema, n, head)) => out.push(SourcePreview {
                name: name.clone(),
                schema: schema.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect(),
                rows: n,
                head: format!("{head}"),
                volume: None,
            }),
            Err(e) => diagnostics.push(
                Diagnostic::error(format!("data \"{name}\": {e}"))
                    .at_opt(doc.span_of(&[PathSeg::Key("data".into()), PathSeg::Key(name.clone())])),
            ),
        }
    }
    if diagnostics.iter().any(Diagnostic::is_error) {
        return Err(fail(source, diagnostics));
    }
    Ok(out)
}

/// An engine source's columns, row count and first `rows` rows, as the engine answers them.
fn preview_on_engine(
    source: &spec::DataSource,
    name: &str,
    spec_dir: &Path,
    rows: usize,
) -> Result<SourcePreview, String> {
    let query = data::engine::source::query_of(source, name, spec_dir).map_err(|(_, message)| message)?;
    let n = query.rows()?;
    let head = query.run(&format!("SELECT * FROM ({}) AS rows LIMIT {rows}", query.query))?;
    Ok(SourcePreview {
        name: name.to_string(),
        schema: head.schema().iter().map(|(k, v)| (k.to_string(), v.to_string())).collect(),
        rows: usize::try_from(n).unwrap_or(usize::MAX),
        head: format!("{head}"),
        volume: None,
    })
}

/// Whether a byte offset lies inside one of the spec's `[data.NAME]` tables.
fn in_data_table(doc: &SpecDoc, offset: usize) -> bool {
    let Some(data) = doc.get(&[PathSeg::Key("data".into())]) else { return false };
    data.entries().iter().any(|e| {
        let start = e.key_span.start.min(e.value.span.start);
        (start..=value_end(&e.value)).contains(&offset)
    })
}

/// The last byte a value or anything below it covers.
fn value_end(value: &spec::SpannedValue) -> usize {
    let own = value.span.end;
    let inner = match &value.kind {
        spec::ValueKind::Table(entries) => entries.iter().map(|e| value_end(&e.value)).max(),
        spec::ValueKind::Array(items) => items.iter().map(value_end).max(),
        _ => None,
    };
    inner.map_or(own, |i| i.max(own))
}

/// Run a source's plan, reading only the columns its charts use when they all exist (else every
/// column, so a missing-column diagnostic can list the real ones), and those of `maybe` (columns
/// a chart would take by convention) that exist.
fn collect_source(
    frame: &polars::prelude::LazyFrame,
    wanted: Option<&[String]>,
    maybe: &[String],
    name: &str,
) -> Result<Table, String> {
    use polars::prelude::col;
    let df = data::contained::contain(|| {
        let mut lf = frame.clone();
        let schema = lf.collect_schema().map_err(|e| data::transform::first_line(&e.to_string()))?;
        if let Some(columns) = wanted
            && !(columns.is_empty() && maybe.is_empty())
            && columns.iter().all(|c| schema.contains(c))
        {
            let present = maybe.iter().filter(|c| schema.contains(c.as_str()) && !columns.contains(c));
            lf = lf.select(columns.iter().chain(present).map(|c| col(c.as_str())).collect::<Vec<_>>());
        }
        lf.collect().map_err(|e| format!("the transforms fail: {}", data::transform::first_line(&e.to_string())))
    })??;
    data::load::frame_to_table(&df, &format!("data \"{name}\" after its transforms"))
        .map_err(|e| format!("{e}; {}", e.hint()))
}

/// Evaluate every selection of a valid spec against its loaded table; problems (unknown columns,
/// ranges on text) become diagnostics pointing into the spec.
fn evaluate_selections(
    spec: Option<&Spec>,
    doc: &SpecDoc,
    tables: &BTreeMap<String, Table>,
) -> (BTreeMap<String, Highlight>, Vec<Diagnostic>) {
    let mut highlights = BTreeMap::new();
    let mut diagnostics = Vec::new();
    let Some(spec) = spec else { return (highlights, diagnostics) };
    for (name, selection) in &spec.selection {
        let Some(table) = tables.get(&selection.data) else { continue };
        match selection::evaluate(name, selection, table) {
            Ok(h) => {
                highlights.insert(name.clone(), h);
            }
            Err(e) => {
                let mut d = Diagnostic::error(e.message).with_hint(e.hint);
                if let Some(span) = doc.key_span_of(&e.path).or_else(|| doc.span_of(&e.path)) {
                    d = d.at(span);
                }
                diagnostics.push(d);
            }
        }
    }
    (highlights, diagnostics)
}

/// Every rule named in a `[lint]` or chart `lint` table must exist.
fn check_lint_config(spec: &Spec, doc: &SpecDoc) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let mut tables: Vec<(Vec<PathSeg>, &spec::LintConfig)> = Vec::new();
    if let Some(config) = &spec.lint {
        tables.push((vec![PathSeg::Key("lint".into())], config));
    }
    for (index, chart) in spec.chart.iter().enumerate() {
        if let Some(config) = &chart.lint {
            tables.push((spec::chart_path(index, "lint"), config));
        }
    }
    let keys = lint::rule_keys();
    for (base, config) in tables {
        for (list_key, list) in [("allow", &config.allow), ("deny", &config.deny)] {
            for (i, name) in list.iter().flatten().enumerate() {
                if lint::find_rule(name).is_some() {
                    continue;
                }
                let mut path = base.clone();
                path.extend([PathSeg::Key(list_key.into()), PathSeg::Index(i)]);
                let hint = spec::suggest::hint(name, &keys, "rules", true);
                out.push(
                    Diagnostic::error(format!("no lint rule `{name}`"))
                        .with_hint(hint)
                        .with_label("unknown rule")
                        .at_opt(doc.span_of(&path)),
                );
            }
        }
    }
    out
}

/// The data sources of a spec that failed validation elsewhere, where they are valid themselves.
fn valid_sources(doc: &Value) -> BTreeMap<String, spec::DataSource> {
    let mut out = BTreeMap::new();
    if let Some(Value::Object(map)) = doc.get("data") {
        for (name, value) in map {
            // A source naming none of `path`, `values` and `from` is already reported.
            if let Ok(source) = serde_json::from_value::<spec::DataSource>(value.clone())
                && (source.path.is_some() || source.values.is_some() || source.from.is_some())
            {
                out.insert(name.clone(), source);
            }
        }
    }
    out
}

/// The column references of one chart table: `(column, spec path)` for every column-bearing key.
fn chart_fields(index: usize, chart: &Value) -> Vec<(String, Vec<PathSeg>)> {
    let Some(kind) = chart.get("kind").and_then(Value::as_str) else { return Vec::new() };
    let mut out = Vec::new();
    for key in mark::column_keys(kind) {
        let Some(value) = chart.get(*key) else { continue };
        let base = vec![PathSeg::Key("chart".into()), PathSeg::Index(index), PathSeg::Key(key.to_string())];
        match (*key, value) {
            // A table of columns by name (faces' `features`).
            ("features", Value::Object(map)) => out.extend(map.iter().filter_map(|(k, v)| {
                let mut path = base.clone();
                path.push(PathSeg::Key(k.clone()));
                v.as_str().map(|s| (s.to_string(), path))
            })),
            // A tree's columns (treemap, hypertree).
            ("tree", Value::Object(map)) => out.extend(named_fields(map, &["id", "parent", "path"], &base)),
            // A line's band edges.
            ("band", Value::Object(map)) => out.extend(named_fields(map, &["lower", "upper"], &base)),
            // A band computed from the rows (`band = "ci95"`) names no column.
            ("band", Value::String(_)) => {}
            _ => out.extend(field_refs(value, base)),
        }
    }
    // The columns that split a faceted chart into panels.
    if let Some(facet) = chart.get("facet") {
        let base = vec![PathSeg::Key("chart".into()), PathSeg::Index(index), PathSeg::Key("facet".into())];
        match facet {
            Value::String(field) => out.push((field.clone(), base)),
            Value::Object(map) => out.extend(named_fields(map, &["row", "column"], &base)),
            _ => {}
        }
    }
    // The columns listed for hover texts.
    if let Some(list @ Value::Array(_)) = chart.get("tooltip") {
        let base = vec![PathSeg::Key("chart".into()), PathSeg::Index(index), PathSeg::Key("tooltip".into())];
        out.extend(field_refs(list, base));
    }
    out
}

/// Column names with the spec paths that name them.
type FieldRefs = Vec<(String, Vec<PathSeg>)>;

/// The string values of `keys` in a table, with their spec paths.
fn named_fields(map: &serde_json::Map<String, Value>, keys: &[&str], base: &[PathSeg]) -> Vec<(String, Vec<PathSeg>)> {
    keys.iter()
        .filter_map(|k| {
            let mut path = base.to_vec();
            path.push(PathSeg::Key(k.to_string()));
            map.get(*k).and_then(Value::as_str).map(|s| (s.to_string(), path))
        })
        .collect()
}

/// A network chart's node table: its data source and the columns named in `nodes`.
fn node_fields(index: usize, chart: &Value) -> Option<(String, FieldRefs)> {
    let Value::Object(nodes) = chart.get("nodes")? else { return None };
    let data = nodes.get("data")?.as_str()?.to_string();
    let base = vec![PathSeg::Key("chart".into()), PathSeg::Index(index), PathSeg::Key("nodes".into())];
    let mut fields = named_fields(nodes, &["id", "label", "size", "x", "y"], &base);
    if let Some(color) = nodes.get("color") {
        let mut path = base.clone();
        path.push(PathSeg::Key("color".into()));
        fields.extend(field_refs(color, path));
    }
    Some((data, fields))
}

/// The columns each data source must provide: the union of its charts' column references.
/// Sources with a chart whose kind is unknown are read whole.
fn needed_columns(doc: &Value) -> BTreeMap<String, std::collections::BTreeSet<String>> {
    let mut out: BTreeMap<String, std::collections::BTreeSet<String>> = BTreeMap::new();
    let Some(Value::Array(charts)) = doc.get("chart") else { return out };
    for (index, chart) in charts.iter().enumerate() {
        let Some(data_name) = chart.get("data").and_then(Value::as_str) else { continue };
        out.entry(data_name.to_string()).or_default().extend(chart_fields(index, chart).into_iter().map(|(f, _)| f));
        if let Some((nodes, fields)) = node_fields(index, chart) {
            out.entry(nodes).or_default().extend(fields.into_iter().map(|(f, _)| f));
        }
    }
    // A selection reads its own columns, which its charts need not draw.
    if let Some(Value::Object(selections)) = doc.get("selection") {
        for selection in selections.values() {
            let Some(data_name) = selection.get("data").and_then(Value::as_str) else { continue };
            let Some(set) = out.get_mut(data_name) else { continue };
            for key in ["range", "categories"] {
                if let Some(Value::Object(columns)) = selection.get(key) {
                    set.extend(columns.keys().cloned());
                }
            }
        }
    }
    out
}

/// The columns each data source may provide for the conventional defaults of its charts' keys
/// ([`spec::defaults::candidate_columns`]): read when the source has them.
fn conventional_columns(doc: &Value) -> BTreeMap<String, std::collections::BTreeSet<String>> {
    let mut out: BTreeMap<String, std::collections::BTreeSet<String>> = BTreeMap::new();
    for chart in doc.get("chart").and_then(Value::as_array).into_iter().flatten() {
        let Some(data_name) = chart.get("data").and_then(Value::as_str) else { continue };
        let names = spec::defaults::candidate_columns(chart).into_iter().map(str::to_owned);
        out.entry(data_name.to_string()).or_default().extend(names);
    }
    out
}

/// Check that every column a chart names exists in its data source. Works on the raw spec so it
/// runs even when other parts of the spec have errors.
fn check_columns(doc: &Value, spans: &SpecDoc, tables: &BTreeMap<String, Table>) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let Some(Value::Array(charts)) = doc.get("chart") else { return out };
    for (index, chart) in charts.iter().enumerate() {
        let chart_name = chart.get("name").and_then(Value::as_str).unwrap_or("?");
        let own = chart.get("data").and_then(Value::as_str).map(|d| (d.to_string(), chart_fields(index, chart)));
        for (data_name, fields) in own.into_iter().chain(node_fields(index, chart)) {
            let Some(table) = tables.get(&data_name) else { continue };
            out.extend(missing_columns(chart_name, &data_name, table, fields, spans));
        }
    }
    out
}

/// Diagnostics for the fields that `table` lacks.
fn missing_columns(
    chart_name: &str,
    data_name: &str,
    table: &Table,
    fields: Vec<(String, Vec<PathSeg>)>,
    spans: &SpecDoc,
) -> Vec<Diagnostic> {
    fields
        .into_iter()
        .filter(|(field, _)| table.column(field).is_none())
        .map(|(field, path)| {
            let (message, hint) = mark::encode::missing_column(data_name, &field, table);
            let d = Diagnostic::error(format!("chart \"{chart_name}\": {message}"))
                .with_hint(hint)
                .with_label("no such column");
            match spans.span_of(&path) {
                Some(span) => d.at(span),
                None => d,
            }
        })
        .collect()
}

/// Column names in a channel value: `"col"`, `{ field = "col" }`, or a list of those.
fn field_refs(value: &Value, path: Vec<PathSeg>) -> Vec<(String, Vec<PathSeg>)> {
    match value {
        Value::String(s) => vec![(s.clone(), path)],
        Value::Object(map) => match map.get("field") {
            Some(Value::String(s)) => {
                let mut p = path;
                p.push(PathSeg::Key("field".into()));
                vec![(s.clone(), p)]
            }
            _ => Vec::new(),
        },
        Value::Array(items) => items
            .iter()
            .enumerate()
            .flat_map(|(i, v)| {
                let mut p = path.clone();
                p.push(PathSeg::Index(i));
                field_refs(v, p)
            })
            .collect(),
        _ => Vec::new(),
    }
}

/// Which outputs to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Formats {
    /// `NAME.svg`.
    pub svg: bool,
    /// `NAME.png`.
    pub png: bool,
    /// `NAME.csv` (derived geometry).
    pub csv: bool,
    /// `NAME.geojson` (derived geometry, for kinds that have it).
    pub geojson: bool,
    /// `NAME.glb`, glTF 2.0 binary (3-D surfaces, for kinds that make them).
    pub glb: bool,
    /// `NAME.ply` (3-D surfaces, for kinds that make them).
    pub ply: bool,
    /// `NAME.obj` (3-D surfaces, for kinds that make them).
    pub obj: bool,
}

impl Formats {
    /// The file extensions these formats write.
    pub fn extensions(&self) -> impl Iterator<Item = &'static str> {
        [
            (self.svg, "svg"),
            (self.png, "png"),
            (self.csv, "csv"),
            (self.geojson, "geojson"),
            (self.glb, "glb"),
            (self.ply, "ply"),
            (self.obj, "obj"),
        ]
        .into_iter()
        .filter_map(|(on, ext)| on.then_some(ext))
    }
}

/// The files a loaded spec was read from: the spec itself and each data source's file, so that
/// no output overwrites them.
pub fn input_files(loaded: &Loaded) -> Vec<PathBuf> {
    let spec_dir = loaded.source.path.parent().map(Path::to_path_buf).unwrap_or_else(|| PathBuf::from("."));
    // An engine source's path is the cluster's to read, not an input of this process.
    let local = loaded.spec.data.values().filter(|source| source.engine.is_none());
    let data = local.filter_map(|source| source.path.as_deref()).map(|p| spec_dir.join(p));
    std::iter::once(loaded.source.path.clone()).chain(data).collect()
}

/// Options of `dataink render`.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    /// Output folder (created if missing).
    pub out_dir: PathBuf,
    /// Which files to write.
    pub formats: Formats,
    /// Only these charts (all if empty).
    pub charts: Vec<String>,
    /// Device pixels per CSS pixel for PNG output.
    pub scale: f64,
    /// Called once, with the folder, when another run holds the output folder's lock and this
    /// one waits for it.
    pub waiting: Option<fn(&Path)>,
}

/// What rendering one chart produced.
#[derive(Debug)]
pub struct Rendered {
    /// Chart name.
    pub name: String,
    /// Files written.
    pub files: Vec<PathBuf>,
    /// Warnings raised while drawing.
    pub warnings: Vec<String>,
    /// What the lint rules found.
    pub lint: ChartLint,
}

/// Why [`render_all`] failed, with the charts it still drew and wrote (their files exist).
#[derive(Debug, Default)]
pub struct RenderFailure {
    /// The charts written before or beside the failures, in spec order.
    pub rendered: Vec<Rendered>,
    /// Every problem: a chart that could not be drawn or written, or one that stopped all of them.
    pub diagnostics: Vec<Diagnostic>,
}

impl From<Vec<Diagnostic>> for RenderFailure {
    fn from(diagnostics: Vec<Diagnostic>) -> RenderFailure {
        RenderFailure { rendered: Vec::new(), diagnostics }
    }
}

/// One chart drawn and linted.
#[derive(Debug)]
pub struct Linted {
    /// Position among the spec's charts.
    pub index: usize,
    /// The drawn chart.
    pub output: ChartOutput,
    /// What the lint rules found.
    pub lint: ChartLint,
}

/// Lint one drawn chart under the spec's configuration, placing each finding in the spec file.
pub fn lint_chart(loaded: &Loaded, index: usize, chart: &spec::Chart, output: &ChartOutput) -> ChartLint {
    let empty = Table::default();
    let table = loaded.tables.get(&chart.data).unwrap_or(&empty);
    let subject = lint::Subject { chart, index, table, nodes: node_table(loaded, chart), output };
    let mut result = lint::lint_chart(&subject, loaded.spec.lint.as_ref());
    for f in result.findings.iter_mut().chain(result.allowed.iter_mut()) {
        // Point at the deepest part of the path that exists in the spec.
        let mut path = f.segments.clone();
        while !path.is_empty() {
            if let Some(span) = loaded.doc.key_span_of(&path).or_else(|| loaded.doc.span_of(&path)) {
                let (line, column) = loaded.source.line_col(span.start);
                f.line = Some(line);
                f.column = Some(column);
                break;
            }
            path.pop();
        }
    }
    result
}

/// Draw and lint the selected charts (all when `names` is empty) in parallel, in spec order.
pub fn draw_and_lint(loaded: &Loaded, names: &[String]) -> Result<Vec<Linted>, Vec<Diagnostic>> {
    let selected = select_charts(&loaded.spec, names).map_err(|d| vec![d])?;
    let results: Vec<Result<Linted, Diagnostic>> = selected
        .par_iter()
        .map(|(index, chart)| {
            let output = draw_chart(loaded, *index, chart).map_err(|e| mark_diagnostic(loaded, &e))?;
            let lint = lint_chart(loaded, *index, chart, &output);
            Ok(Linted { index: *index, output, lint })
        })
        .collect();
    let (ok, errors): (Vec<_>, Vec<_>) = results.into_iter().partition(Result::is_ok);
    if errors.is_empty() {
        let mut linted: Vec<Linted> = ok.into_iter().filter_map(Result::ok).collect();
        one_finding_per_source(loaded, linted.iter_mut().map(|l| (l.index, &mut l.lint)));
        Ok(linted)
    } else {
        Err(errors.into_iter().filter_map(Result::err).collect())
    }
}

/// The node table a network chart names, when it has one.
pub(crate) fn node_table<'a>(loaded: &'a Loaded, chart: &spec::Chart) -> Option<&'a Table> {
    mark::technique(&chart.kind).node_data().and_then(|data| loaded.tables.get(data))
}

/// Charts selected by name, or a diagnostic naming the unknown ones.
pub fn select_charts<'s>(spec: &'s Spec, names: &[String]) -> Result<Vec<(usize, &'s spec::Chart)>, Diagnostic> {
    if names.is_empty() {
        return Ok(spec.chart.iter().enumerate().collect());
    }
    let mut out = Vec::new();
    for name in names {
        match spec.chart.iter().enumerate().find(|(_, c)| &c.name == name) {
            Some(found) => out.push(found),
            None => {
                let known: Vec<&str> = spec.chart.iter().map(|c| c.name.as_str()).collect();
                let hint = spec::suggest::hint(name, &known, "charts", false);
                return Err(Diagnostic::error(format!("no chart named `{name}` in the spec")).with_hint(hint));
            }
        }
    }
    Ok(out)
}

/// Draw one chart of a loaded spec.
pub fn draw_chart(loaded: &Loaded, index: usize, chart: &spec::Chart) -> Result<ChartOutput, MarkError> {
    let empty = Table::default();
    let volume = loaded.volumes.get(&chart.data);
    if let Some(volume) = volume.filter(|_| !mark::technique(&chart.kind).info().draws_volumes) {
        return Err(volume_for_table_kind(chart, volume).in_chart(index, &chart.name));
    }
    let table = loaded.tables.get(&chart.data).or(volume.map(|_| &empty)).ok_or_else(|| {
        MarkError::at(&["data"], format!("data \"{}\" was not loaded", chart.data), "").in_chart(index, &chart.name)
    })?;
    let highlight = chart.highlight.as_ref().and_then(|name| loaded.highlights.get(name));
    let mut output = mark::draw_in(
        &mark::ChartContext::new(chart, index, table)
            .with_highlight(highlight)
            .with_nodes(node_table(loaded, chart))
            .with_volume(volume)
            .with_plan(loaded.plans.get(&chart.data)),
    )?;
    attach_tooltips(index, chart, table, &mut output);
    Ok(output)
}

/// The error for a chart of a table kind whose data is a volume: it has no rows or columns.
fn volume_for_table_kind(chart: &spec::Chart, volume: &data::volume::Volume) -> MarkError {
    let [nx, ny, nz] = volume.dims();
    let volume_kinds = mark::registry::names_where(|k| k.draws_volumes);
    let hint = if volume_kinds.is_empty() {
        "no chart kind of this version draws volumes; `dataink data SPEC NAME` describes the volume".to_string()
    } else {
        format!("volumes are drawn by kind {}", volume_kinds.join(", "))
    };
    MarkError::at(
        &["data"],
        format!(
            "data \"{}\" is a volume ({nx} × {ny} × {nz} voxels), and kind \"{}\" draws the rows of a table",
            chart.data,
            chart.kind.name()
        ),
        hint,
    )
}

/// Hover texts for the chart's data marks, as its `tooltip` key asks: the values of its own
/// columns (default), of the listed ones, or none.
fn attach_tooltips(index: usize, chart: &spec::Chart, table: &Table, output: &mut ChartOutput) {
    let (fields, unlimited) = match &chart.tooltip {
        Some(spec::Tooltip::Show(false)) => return,
        Some(spec::Tooltip::Fields(fields)) => (fields.clone(), true),
        Some(spec::Tooltip::Show(true)) | None => {
            let value = serde_json::to_value(chart).unwrap_or(Value::Null);
            let mut fields: Vec<String> = Vec::new();
            for (field, _) in chart_fields(index, &value) {
                if !fields.contains(&field) {
                    fields.push(field);
                }
            }
            (fields, false)
        }
    };
    let rows_index_table = mark::technique(&chart.kind).node_data().is_none();
    mark::tooltip::Tooltips { table, fields, rows_index_table, unlimited }.attach(&mut output.scene);
}

/// A mark error as a diagnostic pointing into the spec.
pub fn mark_diagnostic(loaded: &Loaded, error: &MarkError) -> Diagnostic {
    let mut d = Diagnostic::error(error.message.clone());
    if !error.hint.is_empty() {
        d = d.with_hint(error.hint.clone());
    }
    let mut path = error.path.clone();
    // Point at the deepest part of the path that exists in the spec.
    while !path.is_empty() {
        if let Some(span) = loaded.doc.span_of(&path) {
            return d.at(span);
        }
        path.pop();
    }
    d
}

/// The pixel size of chart `index`'s PNG at `scale` (its canvas as drawn over its table), or the
/// error at its `size` when the renderer would refuse that canvas; checked before any drawing.
pub fn png_canvas(loaded: &Loaded, index: usize, chart: &spec::Chart, scale: f64) -> Result<(u32, u32), Diagnostic> {
    let [w, h] = match loaded.tables.get(&chart.data) {
        Some(table) => mark::canvas_size_in(chart, table),
        None => mark::canvas_size(chart),
    };
    render::png::check_canvas(w, h, scale).map_err(|e| {
        mark_diagnostic(
            loaded,
            &MarkError::at(&["size"], e.to_string(), "reduce `size` or `--scale`").in_chart(index, &chart.name),
        )
    })
}

/// Draw and write the selected charts in parallel. `progress` is called once per finished chart.
/// When some charts fail, the others are still written and the failure lists them.
pub fn render_all(
    loaded: &Loaded,
    options: &RenderOptions,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Vec<Rendered>, RenderFailure> {
    let selected = select_charts(&loaded.spec, &options.charts).map_err(|d| vec![d])?;
    // Check every canvas before any drawing allocates it.
    let mut problems = Vec::new();
    for (index, chart) in &selected {
        if options.formats.png
            && let Err(problem) = png_canvas(loaded, *index, chart, options.scale)
        {
            problems.push(problem);
        }
    }
    if !problems.is_empty() {
        return Err(problems.into());
    }
    let _lock = output::OutputLock::acquire(&options.out_dir, || {
        if let Some(waiting) = options.waiting {
            waiting(&options.out_dir);
        }
    })
    .map_err(|e| vec![Diagnostic::error(e.to_string())])?;
    let planned: Vec<PathBuf> = selected
        .iter()
        .flat_map(|(_, chart)| {
            options.formats.extensions().map(|ext| options.out_dir.join(format!("{}.{ext}", chart.name)))
        })
        .collect();
    output::refuse_inputs(&planned, &input_files(loaded)).map_err(|clash| {
        vec![Diagnostic::error(clash.to_string()).with_hint("give another --out folder, or rename the chart")]
    })?;
    let results: Vec<Result<(usize, Rendered), Diagnostic>> = selected
        .par_iter()
        .map(|(index, chart)| {
            let out = timed(&format!("draw chart \"{}\"", chart.name), || draw_chart(loaded, *index, chart))
                .map_err(|e| mark_diagnostic(loaded, &e))?;
            let files = timed(&format!("render and write chart \"{}\"", chart.name), || {
                write_chart(&out, &chart.name, loaded.tables.get(&chart.data), options)
            })?;
            let lint = timed(&format!("lint chart \"{}\"", chart.name), || lint_chart(loaded, *index, chart, &out));
            progress(&chart.name);
            Ok((
                *index,
                Rendered {
                    name: chart.name.clone(),
                    files,
                    warnings: out.warnings.iter().map(ToString::to_string).collect(),
                    lint,
                },
            ))
        })
        .collect();
    let mut rendered = Vec::new();
    let mut errors = Vec::new();
    for r in results {
        match r {
            Ok(x) => rendered.push(x),
            Err(d) => errors.push(d),
        }
    }
    one_finding_per_source(loaded, rendered.iter_mut().map(|(i, r)| (*i, &mut r.lint)));
    let rendered: Vec<Rendered> = rendered.into_iter().map(|(_, r)| r).collect();
    if errors.is_empty() { Ok(rendered) } else { Err(RenderFailure { rendered, diagnostics: errors }) }
}

/// Findings about a whole data source (DI004 dropped rows) kept once per source, naming its
/// charts, rather than once per chart; `lints` pairs each chart's index with its findings.
fn one_finding_per_source<'l>(loaded: &Loaded, lints: impl Iterator<Item = (usize, &'l mut ChartLint)>) {
    let mut by_source: Vec<(&str, &mut ChartLint)> =
        lints.filter_map(|(index, lint)| Some((loaded.spec.chart.get(index)?.data.as_str(), lint))).collect();
    lint::rules::one_dropped_rows_per_source(&mut by_source);
}

fn write_chart(
    out: &ChartOutput,
    name: &str,
    table: Option<&Table>,
    options: &RenderOptions,
) -> Result<Vec<PathBuf>, Diagnostic> {
    let mut files = Vec::new();
    let write = |path: PathBuf, bytes: &[u8], files: &mut Vec<PathBuf>| -> Result<(), Diagnostic> {
        output::write_file(&path, bytes)
            .map_err(|e| Diagnostic::error(format!("cannot write `{}`: {e}", path.display())))?;
        files.push(path);
        Ok(())
    };
    if options.formats.svg {
        let svg = render::svg::to_svg(&out.scene);
        write(options.out_dir.join(format!("{name}.svg")), svg.as_bytes(), &mut files)?;
    }
    if options.formats.png {
        let png = render::png::to_png(&out.scene, options.scale)
            .map_err(|e| Diagnostic::error(format!("chart \"{name}\": {e}")))?;
        write(options.out_dir.join(format!("{name}.png")), &png, &mut files)?;
    }
    if options.formats.csv {
        let empty = Table::default();
        let csv = out.derived.to_csv(table.unwrap_or(&empty));
        write(options.out_dir.join(format!("{name}.csv")), csv.as_bytes(), &mut files)?;
    }
    if let (true, Some(geojson)) = (options.formats.geojson, &out.geojson) {
        let text = serde_json::to_string(geojson)
            .map_err(|e| Diagnostic::error(format!("chart \"{name}\": cannot write GeoJSON: {e}")))?;
        write(options.out_dir.join(format!("{name}.geojson")), text.as_bytes(), &mut files)?;
    }
    if !out.meshes.is_empty() {
        use render::meshfile::{glb::to_glb, obj::to_obj, ply::to_ply};
        if options.formats.glb {
            write(options.out_dir.join(format!("{name}.glb")), &to_glb(&out.meshes), &mut files)?;
        }
        if options.formats.ply {
            write(options.out_dir.join(format!("{name}.ply")), &to_ply(&out.meshes), &mut files)?;
        }
        if options.formats.obj {
            write(options.out_dir.join(format!("{name}.obj")), to_obj(&out.meshes).as_bytes(), &mut files)?;
        }
    }
    Ok(files)
}
