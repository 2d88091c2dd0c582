//! A chart's annotations (`[[chart.annotate]]`): reference rules, shaded bands, text at a data
//! point and arrows, written in the data's own values. The four forms share one table so that a
//! misspelt key is reported against every key an annotation may have; [`Annotation::form`] tells
//! them apart and says what is missing or does not belong.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A note drawn over an x/y chart: a rule (`y = 50`, `x = "2014-06-01"`), a shaded band
/// (`x = [a, b]` or `y = [a, b]`), text at a data point (`text` with `at = [x, y]`) or an arrow
/// (`arrow = [[x0, y0], [x1, y1]]`). `x` is the horizontal axis and `y` the vertical one.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Annotation {
    /// A vertical rule at this x value (a number, a date on a time axis, a category on a band
    /// axis), or a band shaded between two: `x = ["2014-06-01", "2014-09-01"]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(example = &"2014-06-01")]
    pub x: Option<AxisPlace>,
    /// A horizontal rule at this y value, or a band shaded between two: `y = [20, 30]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(example = 50)]
    pub y: Option<AxisPlace>,
    /// Text written at the data point `at`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(example = &"Recession")]
    pub text: Option<String>,
    /// The data point `[x, y]` where `text` is written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(example = example_point())]
    pub at: Option<[AxisValue; 2]>,
    /// An arrow from the first data point to the second, `[[x0, y0], [x1, y1]]`; its `label` is
    /// written at the first.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arrow: Option<[[AxisValue; 2]; 2]>,
    /// Text beside a rule, inside a band, or at an arrow's tail.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(example = &"target")]
    pub label: Option<String>,
    /// Colour of the rule, band, text or arrow (CSS name or `#rrggbb`; default dark grey);
    /// labels are written in the text colour.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(example = &"firebrick")]
    pub color: Option<String>,
    /// Draw a rule or arrow dashed (default false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dash: Option<bool>,
    /// A band's fill opacity, above 0 and at most 1 (default 0.15).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 1), example = 0.15)]
    pub opacity: Option<f64>,
    /// Which part of `text` sits at `at`: `"start"`, `"middle"` (default) or `"end"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anchor: Option<TextAnchor>,
}

/// Schema example of `at`.
fn example_point() -> (&'static str, u32) {
    ("2008-10-01", 90)
}

/// One value or two along an axis: a rule at the value, or a band between the two.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum AxisPlace {
    /// A band from one value to the other (in either order).
    Range([AxisValue; 2]),
    /// A rule at the value.
    At(AxisValue),
}

/// A value along an axis: a number, or text (a date such as `"2014-06-01"` on a time axis, a
/// category name on a band axis).
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum AxisValue {
    /// A number on a linear or log axis (or a category written as a number).
    Number(f64),
    /// A date on a time axis or a category on a band axis.
    Text(String),
}

/// Which part of a text sits at its point.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum TextAnchor {
    /// The text starts at the point.
    Start,
    /// The text is centred on the point.
    #[default]
    Middle,
    /// The text ends at the point.
    End,
}

/// The plot axis an annotation's value lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlotAxis {
    /// The horizontal axis.
    X,
    /// The vertical axis.
    Y,
}

impl PlotAxis {
    /// The spec key: `"x"` or `"y"`.
    pub fn key(self) -> &'static str {
        match self {
            PlotAxis::X => "x",
            PlotAxis::Y => "y",
        }
    }
}

/// What an annotation draws, read from the keys it has.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Form<'a> {
    /// A line across the plot at one value of `axis`.
    Rule(PlotAxis, &'a AxisValue),
    /// A shaded band across the plot between two values of `axis`.
    Band(PlotAxis, &'a [AxisValue; 2]),
    /// Text at a data point.
    Text(&'a str, &'a [AxisValue; 2]),
    /// An arrow from the first point to the second.
    Arrow(&'a [[AxisValue; 2]; 2]),
}

impl Form<'_> {
    /// The form's name in messages: "rule", "band", "text note", "arrow".
    pub fn name(&self) -> &'static str {
        match self {
            Form::Rule(..) => "rule",
            Form::Band(..) => "band",
            Form::Text(..) => "text note",
            Form::Arrow(..) => "arrow",
        }
    }
}

/// Why an annotation's keys make no one form, pointing at the key to change.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FormError {
    /// The key at fault (`None`: the annotation as a whole).
    pub key: Option<&'static str>,
    /// What is wrong, written to follow the annotation's name: "has both `x` and `y`".
    pub message: String,
    /// How to fix it.
    pub hint: String,
}

/// The forms written out, for hints.
const FORMS: &str = "write `y = 50` (a rule), `x = [a, b]` (a band), `text = \"…\"` with `at = [x, y]`, or `arrow = [[x0, y0], [x1, y1]]`";

/// The optional keys and the forms they apply to.
const STYLE_KEYS: [(&str, &[&str], &str); 5] = [
    ("label", &["rule", "band", "arrow"], "rules, bands and arrows (`text` is its own label)"),
    ("color", &["rule", "band", "text note", "arrow"], "every form"),
    ("dash", &["rule", "arrow"], "rules and arrows"),
    ("opacity", &["band"], "bands (`x = [a, b]` or `y = [a, b]`)"),
    ("anchor", &["text note"], "`text` written at `at`"),
];

impl Annotation {
    /// What the annotation draws, or why its keys do not make one form: exactly one of a rule or
    /// band on `x`, a rule or band on `y`, `text` with `at`, or `arrow`; and only the style keys
    /// that form uses.
    pub fn form(&self) -> Result<Form<'_>, FormError> {
        let present: Vec<&'static str> = [
            ("x", self.x.is_some()),
            ("y", self.y.is_some()),
            ("text", self.text.is_some() || self.at.is_some()),
            ("arrow", self.arrow.is_some()),
        ]
        .into_iter()
        .filter_map(|(k, on)| on.then_some(k))
        .collect();
        let form = match (present.as_slice(), self) {
            ([], _) => return Err(error(None, "draws nothing: it has none of `x`, `y`, `text` and `arrow`", FORMS)),
            ([first, second, ..], _) => {
                let second = if *second == "text" && self.text.is_none() { "at" } else { second };
                return Err(error(
                    Some(second),
                    &format!("has both `{first}` and `{second}`"),
                    "an annotation draws one thing; write one `[[chart.annotate]]` table each (a point is `text` with `at = [x, y]`)",
                ));
            }
            (["text"], Annotation { text: Some(text), at: Some(at), .. }) => Form::Text(text, at),
            (["text"], Annotation { text: Some(_), .. }) => {
                return Err(error(
                    Some("text"),
                    "has `text` but no `at`",
                    "add `at = [x, y]`, the data point to write it at",
                ));
            }
            (["text"], _) => {
                return Err(error(
                    Some("at"),
                    "has `at` but no `text`",
                    "add `text = \"…\"`, the words to write there",
                ));
            }
            (["arrow"], Annotation { arrow: Some(points), .. }) => Form::Arrow(points),
            ([key], _) => {
                let axis = if *key == "x" { PlotAxis::X } else { PlotAxis::Y };
                match if axis == PlotAxis::X { &self.x } else { &self.y } {
                    Some(AxisPlace::At(v)) => Form::Rule(axis, v),
                    Some(AxisPlace::Range(r)) => Form::Band(axis, r),
                    None => return Err(error(None, "draws nothing", FORMS)),
                }
            }
        };
        let set = [
            self.label.is_some(),
            self.color.is_some(),
            self.dash.is_some(),
            self.opacity.is_some(),
            self.anchor.is_some(),
        ];
        for ((key, forms, owners), on) in STYLE_KEYS.iter().zip(set) {
            if on && !forms.contains(&form.name()) {
                return Err(error(
                    Some(key),
                    &format!("is a {} and does not take `{key}`", form.name()),
                    &format!("`{key}` is for {owners}; remove it"),
                ));
            }
        }
        Ok(form)
    }
}

fn error(key: Option<&'static str>, message: &str, hint: &str) -> FormError {
    FormError { key, message: message.to_owned(), hint: hint.to_owned() }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(toml: &str) -> Annotation {
        let doc = crate::spec::SpecDoc::parse(toml).expect("TOML");
        serde_json::from_value(doc.to_json()).expect("an annotation")
    }

    #[test]
    fn each_form_is_read_from_its_keys() {
        let rule = read("y = 50\nlabel = \"target\"\ndash = true");
        assert_eq!(rule.form(), Ok(Form::Rule(PlotAxis::Y, &AxisValue::Number(50.0))));
        let date = read("x = \"2014-06-01\"");
        assert_eq!(date.form(), Ok(Form::Rule(PlotAxis::X, &AxisValue::Text("2014-06-01".into()))));
        let band = read("x = [3, 1]\nopacity = 0.3");
        let Ok(Form::Band(PlotAxis::X, [AxisValue::Number(a), AxisValue::Number(b)])) = band.form() else {
            panic!("a band: {:?}", band.form())
        };
        assert_eq!((*a, *b), (3.0, 1.0));
        let text = read("text = \"Recession\"\nat = [\"2008-10-01\", 90]\nanchor = \"start\"");
        assert!(matches!(text.form(), Ok(Form::Text("Recession", _))));
        let arrow = read("arrow = [[1, 2], [3, 4]]\nlabel = \"here\"");
        assert!(matches!(arrow.form(), Ok(Form::Arrow(_))));
    }

    #[test]
    fn keys_that_make_no_one_form_are_named() {
        let none = read("label = \"x\"").form().expect_err("nothing to draw");
        assert_eq!(none.key, None);
        assert!(none.message.starts_with("draws nothing"), "{}", none.message);
        let both = read("x = 1\ny = 2").form().expect_err("two rules");
        assert_eq!((both.key, both.message.as_str()), (Some("y"), "has both `x` and `y`"));
        let at_and_x = read("x = 1\nat = [1, 2]").form().expect_err("rule and point");
        assert_eq!(at_and_x.key, Some("at"));
        assert_eq!(read("text = \"a\"").form().expect_err("no at").key, Some("text"));
        assert_eq!(read("at = [1, 2]").form().expect_err("no text").key, Some("at"));
        let opacity = read("y = 1\nopacity = 0.5").form().expect_err("a rule has no opacity");
        assert_eq!(opacity.key, Some("opacity"));
        assert_eq!(opacity.message, "is a rule and does not take `opacity`");
        assert_eq!(read("text = \"a\"\nat = [1, 2]\nlabel = \"b\"").form().expect_err("text").key, Some("label"));
        assert_eq!(read("y = [1, 2]\nanchor = \"end\"").form().expect_err("band").key, Some("anchor"));
    }

    #[test]
    fn unknown_keys_and_three_values_are_refused() {
        let value = serde_json::json!({ "y": 1, "lable": "x" });
        assert!(serde_json::from_value::<Annotation>(value).is_err());
        let value = serde_json::json!({ "y": [1, 2, 3] });
        assert!(serde_json::from_value::<Annotation>(value).is_err());
    }
}
