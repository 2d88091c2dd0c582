//! Derived geometry as GeoJSON (RFC 7946), kept as plain coordinates and written straight to text
//! when `--format geojson` asks for it: no JSON tree of every coordinate is built, so a chart with
//! millions of vertices costs 16 bytes per vertex here, not a hundred.

use serde::ser::{Serialize, SerializeMap, SerializeSeq, Serializer};

use crate::enrich::contour::{Band, ContourLine};

/// Contour lines as `LineString` features (properties `kind = "line"`, `level`, `closed`) and
/// bands as `MultiPolygon` features (`kind = "band"`, `lower`, `upper`), in data coordinates.
/// Rings repeat their first point; outer rings run counter-clockwise, holes clockwise, as the
/// bands already do.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContourFeatures {
    /// The lines, in order.
    pub lines: Vec<ContourLine>,
    /// The bands, in order.
    pub bands: Vec<Band>,
}

impl ContourFeatures {
    /// The collection as a JSON value (for tests and callers that inspect it).
    pub fn to_value(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or(serde_json::Value::Null)
    }
}

impl Serialize for ContourFeatures {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(2))?;
        map.serialize_entry("type", "FeatureCollection")?;
        map.serialize_entry("features", &Features(self))?;
        map.end()
    }
}

struct Features<'a>(&'a ContourFeatures);

impl Serialize for Features<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(self.0.lines.len() + self.0.bands.len()))?;
        for line in &self.0.lines {
            seq.serialize_element(&LineFeature(line))?;
        }
        for band in &self.0.bands {
            seq.serialize_element(&BandFeature(band))?;
        }
        seq.end()
    }
}

/// One feature: `{"type": "Feature", "properties": …, "geometry": {"type": kind, "coordinates": …}}`.
fn feature<S: Serializer>(
    s: S,
    properties: &impl Serialize,
    kind: &str,
    coordinates: &impl Serialize,
) -> Result<S::Ok, S::Error> {
    struct Geometry<'a, C>(&'a str, &'a C);
    impl<C: Serialize> Serialize for Geometry<'_, C> {
        fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            let mut map = s.serialize_map(Some(2))?;
            map.serialize_entry("type", self.0)?;
            map.serialize_entry("coordinates", self.1)?;
            map.end()
        }
    }
    let mut map = s.serialize_map(Some(3))?;
    map.serialize_entry("type", "Feature")?;
    map.serialize_entry("properties", properties)?;
    map.serialize_entry("geometry", &Geometry(kind, coordinates))?;
    map.end()
}

struct LineFeature<'a>(&'a ContourLine);

impl Serialize for LineFeature<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        #[derive(serde::Serialize)]
        struct Properties {
            kind: &'static str,
            level: f64,
            closed: bool,
        }
        let line = self.0;
        let properties = Properties { kind: "line", level: line.level, closed: line.closed };
        feature(s, &properties, "LineString", &Ring { points: &line.points, close: line.closed })
    }
}

struct BandFeature<'a>(&'a Band);

impl Serialize for BandFeature<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        #[derive(serde::Serialize)]
        struct Properties {
            kind: &'static str,
            lower: f64,
            upper: f64,
        }
        struct Polygons<'a>(&'a [Vec<Vec<(f64, f64)>>]);
        impl Serialize for Polygons<'_> {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.collect_seq(self.0.iter().map(|rings| Rings(rings)))
            }
        }
        struct Rings<'a>(&'a [Vec<(f64, f64)>]);
        impl Serialize for Rings<'_> {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.collect_seq(self.0.iter().map(|r| Ring { points: r, close: true }))
            }
        }
        let band = self.0;
        let properties = Properties { kind: "band", lower: band.lower, upper: band.upper };
        feature(s, &properties, "MultiPolygon", &Polygons(&band.polygons))
    }
}

/// Points as `[x, y]` pairs, the first repeated at the end when `close`.
struct Ring<'a> {
    points: &'a [(f64, f64)],
    close: bool,
}

impl Serialize for Ring<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let closing = self.points.first().filter(|_| self.close);
        s.collect_seq(self.points.iter().chain(closing).map(|&(x, y)| [x, y]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn features_serialise_as_the_json_tree_would() {
        let features = ContourFeatures {
            lines: vec![ContourLine { level: 0.5, points: vec![(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)], closed: true }],
            bands: vec![Band {
                lower: 0.0,
                upper: 1.0,
                polygons: vec![vec![vec![(0.0, 0.0), (2.0, 0.0), (0.0, 2.0)]]],
            }],
        };
        let expected = serde_json::json!({
            "type": "FeatureCollection",
            "features": [
                {
                    "type": "Feature",
                    "properties": { "kind": "line", "level": 0.5, "closed": true },
                    "geometry": { "type": "LineString", "coordinates": [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]] },
                },
                {
                    "type": "Feature",
                    "properties": { "kind": "band", "lower": 0.0, "upper": 1.0 },
                    "geometry": { "type": "MultiPolygon", "coordinates": [[[[0.0, 0.0], [2.0, 0.0], [0.0, 2.0], [0.0, 0.0]]]] },
                },
            ],
        });
        assert_eq!(features.to_value(), expected);
        let text = serde_json::to_string(&features).unwrap();
        assert_eq!(serde_json::from_str::<serde_json::Value>(&text).unwrap(), expected);
    }
}
