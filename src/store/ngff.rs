//! The OME-NGFF `multiscales` metadata: written for version 0.5 (Zarr v3,
//! under the group's `ome` attribute), read from 0.4 and 0.5 (0.4 keeps
//! `multiscales` at the top of the group's attributes).
//!
//! A dataset's `coordinateTransformations` map array indices to world
//! coordinates: `world = index * scale + translation`, per axis, after the
//! multiscale's own transformations (a `scale`, applied last) if any. Only
//! the full-resolution dataset's transformations are used: they are the
//! grid's spacing and origin.

use crate::base::error::{Error, Result};
use crate::base::limits::escape_controls;
use crate::data::grid::GridShape;
use serde_json::{json, Map, Value};

/// What the reader takes from a store's `multiscales[0]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Multiscale {
    /// The path of each dataset, finest first.
    pub paths: Vec<String>,
    /// Axes before the three spatial ones (time, channel): the reader takes index 0 of each.
    pub leading_axes: Vec<String>,
    /// Spacing `(x, y, z)` of the first dataset.
    pub spacing: [f64; 3],
    /// Origin `(x, y, z)` of the first dataset.
    pub origin: [f64; 3],
    /// The NGFF version the metadata declares.
    pub version: String,
}

/// The `ome` attribute of a store written here: NGFF 0.5, axes `z, y, x`,
/// dataset `p` (path `"p"`) at `scale = spacing 2^p` and the grid's origin.
/// (Level `p`'s last plane lies at the grid's last sample, not at
/// `(m_p - 1) 2^p`, when `n - 1` is not a multiple of `2^p`; see
/// [`super::pyramid`]. A viewer that trusts `scale` alone places that one
/// plane up to one coarse step too far.)
pub fn ome_attribute(shape: &GridShape, levels: usize, name: &str) -> Value {
    let datasets: Vec<Value> = (0..levels)
        .map(|p| {
            let f = f64::from(1u32 << p);
            let [sx, sy, sz] = shape.spacing;
            let [ox, oy, oz] = shape.origin;
            json!({
                "path": p.to_string(),
                "coordinateTransformations": [
                    {"type": "scale", "scale": [sz * f, sy * f, sx * f]},
                    {"type": "translation", "translation": [oz, oy, ox]}
                ]
            })
        })
        .collect();
    json!({
        "version": "0.5",
        "multiscales": [{
            "name": name,
            "axes": [
                {"name": "z", "type": "space"},
                {"name": "y", "type": "space"},
                {"name": "x", "type": "space"}
            ],
            "datasets": datasets,
            "type": "subsample",
            "metadata": {"description": "level p holds samples min(i 2^p, n - 1) of level 0 per axis (no filtering)"}
        }]
    })
}

/// Reads `multiscales[0]` from a group's attributes (NGFF 0.5's `ome`
/// attribute, or 0.4's top-level `multiscales`). `label` names the store
/// in messages.
pub fn parse(label: &str, attributes: &Map<String, Value>) -> Result<Multiscale> {
    let err = |m: String| Error::Format { path: label.to_string(), message: m };
    let (root, version) = match attributes.get("ome") {
        Some(ome) => (ome, ome.get("version").and_then(Value::as_str).unwrap_or("0.5").to_string()),
        None => (&Value::Object(attributes.clone()), String::new()),
    };
    let ms = root.get("multiscales").and_then(Value::as_array).and_then(|m| m.first()).ok_or_else(|| {
        err("no OME-NGFF 'multiscales' metadata in the group's attributes: open an OME-Zarr image \
                 (the group that holds 'multiscales'), not a plain Zarr array or a plate/well group"
            .into())
    })?;
    let version = if version.is_empty() {
        ms.get("version").and_then(Value::as_str).unwrap_or("0.4").to_string()
    } else {
        version
    };
    let datasets = ms
        .get("datasets")
        .and_then(Value::as_array)
        .filter(|d| !d.is_empty())
        .ok_or_else(|| err("the multiscales metadata lists no datasets".into()))?;
    let paths = datasets
        .iter()
        .map(|d| {
            d.get("path").and_then(Value::as_str).map(str::to_string).ok_or_else(|| err("a dataset has no path".into()))
        })
        .collect::<Result<Vec<_>>>()?;
    for p in &paths {
        if p.is_empty() || p.split('/').any(|c| c.is_empty() || c == "." || c == "..") {
            return Err(err(format!("dataset path '{}' is not a relative path inside the store", escape_controls(p))));
        }
    }
    let axes = axis_names(ms);
    let rank = axes.as_ref().map_or(0, Vec::len);
    if let Some(axes) = &axes {
        if rank < 3 {
            return Err(err(format!(
                "the image has {rank} axes ({}): a volume needs three spatial axes (z, y, x)",
                axes.join(", ")
            )));
        }
    }
    let leading_axes = axes.as_ref().map(|a| a[..a.len() - 3].to_vec()).unwrap_or_default();
    let (scale, translation) = transformations(datasets[0].get("coordinateTransformations"), label)?;
    let (outer_scale, outer_translation) = transformations(ms.get("coordinateTransformations"), label)?;
    let last3 = |v: &Option<Vec<f64>>, default: f64| -> [f64; 3] {
        match v {
            Some(v) if v.len() >= 3 => {
                let n = v.len();
                [v[n - 1], v[n - 2], v[n - 3]]
            }
            _ => [default; 3],
        }
    };
    let (s, t) = (last3(&scale, 1.0), last3(&translation, 0.0));
    let (os, ot) = (last3(&outer_scale, 1.0), last3(&outer_translation, 0.0));
    let spacing = [0, 1, 2].map(|a| s[a] * os[a]);
    let origin = [0, 1, 2].map(|a| t[a] * os[a] + ot[a]);
    if spacing.iter().any(|s| !(s.is_finite() && *s > 0.0)) || origin.iter().any(|o| !o.is_finite()) {
        return Err(err(format!(
            "the first dataset's coordinateTransformations give spacing {spacing:?} and origin {origin:?}: \
             the scale must be finite and positive, the translation finite"
        )));
    }
    Ok(Multiscale { paths, leading_axes, spacing, origin, version })
}

/// The axis names of a multiscale (0.4/0.5: objects with `name`; 0.3: strings).
fn axis_names(ms: &Value) -> Option<Vec<String>> {
    let axes = ms.get("axes")?.as_array()?;
    Some(
        axes.iter()
            .map(|a| match a {
                Value::String(s) => escape_controls(s),
                other => escape_controls(other.get("name").and_then(Value::as_str).unwrap_or("?")),
            })
            .collect(),
    )
}

/// A transformation's `scale`, per axis (`None`: not given).
type Scale = Option<Vec<f64>>;
/// A transformation's `translation`, per axis (`None`: not given).
type Translation = Option<Vec<f64>>;

/// The `scale` and `translation` of a list of coordinate transformations.
fn transformations(list: Option<&Value>, label: &str) -> Result<(Scale, Translation)> {
    let Some(list) = list.and_then(Value::as_array) else {
        return Ok((None, None));
    };
    let numbers = |v: Option<&Value>| -> Option<Vec<f64>> {
        v?.as_array()?.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>()
    };
    let (mut scale, mut translation) = (None, None);
    for t in list {
        match t.get("type").and_then(Value::as_str) {
            Some("scale") => scale = numbers(t.get("scale")),
            Some("translation") => translation = numbers(t.get("translation")),
            Some("identity") => {}
            other => {
                return Err(Error::Format {
                    path: label.to_string(),
                    message: format!(
                        "coordinate transformation '{}' is not supported: use scale and translation",
                        escape_controls(other.unwrap_or("(none)"))
                    ),
                })
            }
        }
    }
    Ok((scale, translation))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn attrs(v: Value) -> Map<String, Value> {
        v.as_object().unwrap().clone()
    }

    #[test]
    fn what_is_written_reads_back() {
        let shape = GridShape { dims: [10, 20, 30], spacing: [0.5, 1.0, 2.0], origin: [-1.0, 0.0, 3.0] };
        let a = attrs(json!({"ome": ome_attribute(&shape, 4, "ct")}));
        let m = parse("s", &a).unwrap();
        assert_eq!(m.paths, vec!["0", "1", "2", "3"]);
        assert_eq!((m.spacing, m.origin), (shape.spacing, shape.origin));
        assert!(m.leading_axes.is_empty());
        assert_eq!(m.version, "0.5");
    }

    #[test]
    fn ngff_0_4_with_time_and_channel() {
        let a = attrs(json!({"multiscales": [{
            "version": "0.4",
            "axes": [{"name": "t", "type": "time"}, {"name": "c", "type": "channel"},
                     {"name": "z", "type": "space"}, {"name": "y", "type": "space"}, {"name": "x", "type": "space"}],
            "datasets": [{"path": "s0", "coordinateTransformations": [
                {"type": "scale", "scale": [1.0, 1.0, 4.0, 0.5, 0.25]},
                {"type": "translation", "translation": [0.0, 0.0, 10.0, 20.0, 30.0]}]}],
            "coordinateTransformations": [{"type": "scale", "scale": [1.0, 1.0, 2.0, 2.0, 2.0]}]
        }]}));
        let m = parse("s", &a).unwrap();
        assert_eq!(m.leading_axes, vec!["t", "c"]);
        assert_eq!(m.spacing, [0.5, 1.0, 8.0]);
        assert_eq!(m.origin, [60.0, 40.0, 20.0]);
    }

    #[test]
    fn bad_metadata_is_named() {
        let e = |v: Value| parse("store.zarr", &attrs(v)).unwrap_err().to_string();
        assert!(e(json!({})).contains("no OME-NGFF 'multiscales'"));
        assert!(e(json!({"multiscales": [{"datasets": []}]})).contains("no datasets"));
        let two_d = json!({"multiscales": [{"axes": ["y", "x"], "datasets": [{"path": "0"}]}]});
        assert!(e(two_d).contains("three spatial axes"));
        let escape = json!({"multiscales": [{"datasets": [{"path": "../../etc"}]}]});
        assert!(e(escape).contains("not a relative path"));
        let zero = json!({"multiscales": [{"datasets": [{"path": "0",
            "coordinateTransformations": [{"type": "scale", "scale": [0.0, 1.0, 1.0]}]}]}]});
        assert!(e(zero).contains("finite and positive"));
    }
}
