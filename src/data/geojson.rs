//! GeoJSON FeatureCollections (`.geojson`, `format = "geojson"`): one row per feature.
//!
//! - Each feature's `properties` become columns (the union over all features, in the order first
//!   met); a feature whose `properties` is `null` or missing gets nulls. Nested objects and
//!   arrays in properties are kept as JSON text. A property whose values mix numbers and text is
//!   read as text.
//! - Point geometries give columns `lon` and `lat` (the first two coordinates; null for other
//!   geometries and for features without geometry).
//! - Any other geometry (lines, polygons, multi-geometries) is kept whole, kept for a later map
//!   kind: the column `geometry` holds each feature's geometry as GeoJSON text (points included)
//!   and `geometry_type` its type (`"Polygon"`, …). Nothing is projected and no centroids are
//!   computed.
//!
//! A property named like one of these columns is an error, not silently overwritten.

use std::io::Cursor;

use polars::prelude::*;
use serde_json::{Map, Value};

use super::load::first_line;

/// Columns the reader adds beside the properties.
pub const GEOMETRY_COLUMNS: [&str; 4] = ["lon", "lat", "geometry", "geometry_type"];

/// A parsed GeoJSON document as a frame; the error is a message for the user.
pub fn read_geojson(root: &Value) -> Result<DataFrame, String> {
    let Value::Object(top) = root else { return Err("a GeoJSON file must be one JSON object".into()) };
    match top.get("type").and_then(Value::as_str) {
        Some("FeatureCollection") => {}
        Some(other) => {
            return Err(format!(
                "the top-level `type` is `{}`, not `FeatureCollection`; wrap it in {{\"type\": \"FeatureCollection\", \"features\": [...]}}",
                crate::spec::validate::shorten(other)
            ));
        }
        None => return Err("the top-level object has no `type`; GeoJSON data must be a FeatureCollection".into()),
    }
    let Some(Value::Array(features)) = top.get("features") else {
        return Err("the FeatureCollection has no `features` array".into());
    };
    let any_point = features.iter().any(|f| geometry_type(f) == Some("Point"));
    let any_shape = features.iter().any(|f| geometry_type(f).is_some_and(|t| t != "Point"));
    let mut rows = Vec::with_capacity(features.len());
    for (i, feature) in features.iter().enumerate() {
        rows.push(Value::Object(row(i, feature, any_point, any_shape)?));
    }
    if rows.is_empty() {
        return Err("the FeatureCollection has no features".into());
    }
    let bytes = serde_json::to_vec(&rows).map_err(|e| e.to_string())?;
    let df = JsonReader::new(Cursor::new(bytes))
        .with_json_format(JsonFormat::Json)
        .infer_schema_len(None)
        .finish()
        .map_err(|e| first_line(&e))?;
    if df.width() == 0 {
        return Err("the features have no properties and no geometry".into());
    }
    Ok(df)
}

fn geometry_type(feature: &Value) -> Option<&str> {
    feature.get("geometry")?.get("type")?.as_str()
}

/// One feature as a flat record.
fn row(i: usize, feature: &Value, any_point: bool, any_shape: bool) -> Result<Map<String, Value>, String> {
    let Value::Object(f) = feature else { return Err(format!("feature {i} is not a JSON object")) };
    if f.get("type").and_then(Value::as_str) != Some("Feature") {
        return Err(format!("feature {i} has no `\"type\": \"Feature\"`"));
    }
    let mut out = Map::new();
    match f.get("properties") {
        None | Some(Value::Null) => {}
        Some(Value::Object(props)) => {
            for (key, value) in props {
                if GEOMETRY_COLUMNS.contains(&key.as_str()) {
                    return Err(format!(
                        "feature {i} has a property `{key}`, a name this reader gives to a geometry column; rename the property"
                    ));
                }
                let flat = match value {
                    Value::Object(_) | Value::Array(_) => Value::String(value.to_string()),
                    other => other.clone(),
                };
                out.insert(key.clone(), flat);
            }
        }
        Some(_) => return Err(format!("feature {i} has `properties` that are not an object")),
    }
    let geometry = match f.get("geometry") {
        None | Some(Value::Null) => None,
        Some(g @ Value::Object(_)) => Some(g),
        Some(_) => return Err(format!("feature {i} has a `geometry` that is not an object")),
    };
    let kind = match geometry {
        Some(g) => {
            Some(g.get("type").and_then(Value::as_str).ok_or(format!("feature {i} has a geometry without `type`"))?)
        }
        None => None,
    };
    if any_point {
        let (lon, lat) = match (kind, geometry) {
            (Some("Point"), Some(g)) => {
                point(g).ok_or(format!("feature {i} is a Point without two numbers as coordinates"))?
            }
            _ => (Value::Null, Value::Null),
        };
        out.insert("lon".into(), lon);
        out.insert("lat".into(), lat);
    }
    if any_shape {
        out.insert("geometry".into(), geometry.map_or(Value::Null, |g| Value::String(g.to_string())));
        out.insert("geometry_type".into(), kind.map_or(Value::Null, |k| Value::String(k.to_string())));
    }
    Ok(out)
}

/// The longitude and latitude of a Point geometry.
fn point(geometry: &Value) -> Option<(Value, Value)> {
    let coords = geometry.get("coordinates")?.as_array()?;
    let lon = coords.first().filter(|v| v.is_number())?;
    let lat = coords.get(1).filter(|v| v.is_number())?;
    Some((lon.clone(), lat.clone()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<DataFrame, String> {
        read_geojson(&serde_json::from_str(text).expect("test JSON"))
    }

    fn f64s(df: &DataFrame, name: &str) -> Vec<Option<f64>> {
        df.column(name)
            .expect(name)
            .cast(&DataType::Float64)
            .expect("numbers")
            .as_materialized_series()
            .f64()
            .expect("f64")
            .to_vec()
    }

    #[test]
    fn points_become_lon_lat_and_properties_columns() {
        let df = read(
            r#"{"type": "FeatureCollection", "features": [
                {"type": "Feature", "properties": {"mag": 2.5, "place": "A"}, "geometry": {"type": "Point", "coordinates": [-120.5, 35.25, 8.1]}},
                {"type": "Feature", "properties": {"mag": 4, "place": "B", "tags": ["x", "y"]}, "geometry": {"type": "Point", "coordinates": [10, -5]}},
                {"type": "Feature", "properties": null, "geometry": null}
            ]}"#,
        )
        .expect("reads");
        assert_eq!(df.height(), 3);
        assert_eq!(df.get_column_names(), ["mag", "place", "tags", "lon", "lat"]);
        assert_eq!(f64s(&df, "lon"), [Some(-120.5), Some(10.0), None]);
        assert_eq!(f64s(&df, "lat"), [Some(35.25), Some(-5.0), None]);
        assert_eq!(f64s(&df, "mag"), [Some(2.5), Some(4.0), None]);
        let tags =
            df.column("tags").expect("tags").as_materialized_series().str().expect("text").get(1).map(str::to_string);
        assert_eq!(tags.as_deref(), Some(r#"["x","y"]"#));
    }

    #[test]
    fn shapes_are_kept_as_geojson_text() {
        let df = read(
            r#"{"type": "FeatureCollection", "features": [
                {"type": "Feature", "properties": {"name": "sq"}, "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}},
                {"type": "Feature", "properties": {"name": "pt"}, "geometry": {"type": "Point", "coordinates": [3, 4]}}
            ]}"#,
        )
        .expect("reads");
        assert_eq!(df.get_column_names(), ["name", "lon", "lat", "geometry", "geometry_type"]);
        let kinds = df
            .column("geometry_type")
            .expect("type")
            .as_materialized_series()
            .str()
            .expect("text")
            .iter()
            .collect::<Vec<_>>();
        assert_eq!(kinds, [Some("Polygon"), Some("Point")]);
        let shape = df
            .column("geometry")
            .expect("geometry")
            .as_materialized_series()
            .str()
            .expect("text")
            .get(0)
            .unwrap_or("")
            .to_string();
        let back: Value = serde_json::from_str(&shape).expect("geometry text is GeoJSON");
        assert_eq!(back["coordinates"][0][2], serde_json::json!([1, 1]));
        assert_eq!(f64s(&df, "lon"), [None, Some(3.0)]);
    }

    #[test]
    fn mixed_property_types_read_as_text() {
        let df = read(
            r#"{"type": "FeatureCollection", "features": [
                {"type": "Feature", "properties": {"code": 7}, "geometry": null},
                {"type": "Feature", "properties": {"code": "7b"}, "geometry": null}
            ]}"#,
        )
        .expect("reads");
        let codes =
            df.column("code").expect("code").as_materialized_series().str().expect("text").iter().collect::<Vec<_>>();
        assert_eq!(codes, [Some("7"), Some("7b")]);
    }

    #[test]
    fn bad_documents_say_what_is_wrong() {
        assert_eq!(
            read(r#"{"type": "Feature", "properties": {}, "geometry": null}"#).expect_err("a feature"),
            "the top-level `type` is `Feature`, not `FeatureCollection`; wrap it in {\"type\": \"FeatureCollection\", \"features\": [...]}"
        );
        assert_eq!(read("[1, 2]").expect_err("array"), "a GeoJSON file must be one JSON object");
        assert_eq!(
            read(r#"{"type": "FeatureCollection"}"#).expect_err("no features"),
            "the FeatureCollection has no `features` array"
        );
        assert_eq!(
            read(r#"{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": [1]}]}"#)
                .expect_err("array properties"),
            "feature 0 has `properties` that are not an object"
        );
        assert_eq!(
            read(r#"{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"lat": 1}}]}"#)
                .expect_err("clash"),
            "feature 0 has a property `lat`, a name this reader gives to a geometry column; rename the property"
        );
        assert_eq!(
            read(r#"{"type": "FeatureCollection", "features": [{"type": "Feature", "geometry": {"type": "Point", "coordinates": ["a"]}}]}"#)
                .expect_err("bad point"),
            "feature 0 is a Point without two numbers as coordinates"
        );
    }
}
