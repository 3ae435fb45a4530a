//! The names of the built-in datasets.

use crate::base::error::{Error, Result};

/// A built-in dataset; see the module of each for its formula.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Dataset {
    /// 3D Shepp-Logan head phantom: 10 ellipsoids ([`super::shepp_logan`]).
    SheppLogan,
    /// Marschner-Lobb test signal, f_M = 6, alpha = 0.25 ([`super::marschner_lobb`]).
    MarschnerLobb,
    /// Signed distance to a sphere, offset so the surface is the 0.5 isosurface ([`super::sphere`]).
    Sphere,
    /// A linear ramp, exactly trilinear ([`super::ramp`]).
    Ramp,
    /// The constant 0.5 ([`super::constant`]).
    Constant,
    /// A synthetic angiogram: thin vessels in faint tissue ([`super::vessels`]).
    Vessels,
    /// VTK's Wavelet (`vtkRTAnalyticSource`), detail everywhere ([`super::wavelet`]).
    Wavelet,
}

impl Dataset {
    /// Every dataset, in the order the CLI lists them.
    pub const ALL: [Dataset; 7] = [
        Dataset::SheppLogan,
        Dataset::MarschnerLobb,
        Dataset::Sphere,
        Dataset::Ramp,
        Dataset::Constant,
        Dataset::Vessels,
        Dataset::Wavelet,
    ];

    /// The name used by `--dataset` and as the array name of the generated volume.
    pub fn name(self) -> &'static str {
        match self {
            Dataset::SheppLogan => "shepp-logan",
            Dataset::MarschnerLobb => "marschner-lobb",
            Dataset::Sphere => "sphere",
            Dataset::Ramp => "ramp",
            Dataset::Constant => "constant",
            Dataset::Vessels => "vessels",
            Dataset::Wavelet => "wavelet",
        }
    }

    /// Parses a dataset name (case-insensitive; `_` may stand for `-`).
    pub fn parse(s: &str) -> Result<Dataset> {
        let wanted = s.trim().to_ascii_lowercase().replace('_', "-");
        Dataset::ALL.into_iter().find(|d| d.name() == wanted).ok_or_else(|| {
            let names: Vec<&str> = Dataset::ALL.iter().map(|d| d.name()).collect();
            Error::InvalidArgument(format!("unknown dataset '{s}': use one of {}", names.join(", ")))
        })
    }

    /// The field value at box-normalised position `t` in `[0, 1]^3`, in `[0, 1]`.
    pub fn value(self, t: [f64; 3]) -> f64 {
        match self {
            Dataset::SheppLogan => super::shepp_logan::value(t),
            Dataset::MarschnerLobb => super::marschner_lobb::value(t),
            Dataset::Sphere => super::sphere::value(t),
            Dataset::Ramp => super::ramp::value(t),
            Dataset::Constant => super::constant::value(t),
            Dataset::Vessels => super::vessels::value(t),
            Dataset::Wavelet => super::wavelet::value(t),
        }
    }
}

impl Dataset {
    /// One row of samples: `out[i] = self.value([i / (n - 1), ty, tz])`,
    /// `n = out.len()` (`t_x = 0` when `n = 1`), the same values bit for bit;
    /// datasets with a faster way along a row take it.
    pub fn row(self, ty: f64, tz: f64, out: &mut [f64]) {
        match self {
            Dataset::SheppLogan => return super::shepp_logan::row(ty, tz, out),
            Dataset::Vessels => return super::vessels::row(ty, tz, out),
            _ => {}
        }
        let n = out.len();
        for (i, v) in out.iter_mut().enumerate() {
            let tx = if n > 1 { i as f64 / (n - 1) as f64 } else { 0.0 };
            *v = self.value([tx, ty, tz]);
        }
    }
}

impl std::fmt::Display for Dataset {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for d in Dataset::ALL {
            assert_eq!(Dataset::parse(d.name()), Ok(d));
        }
        assert_eq!(Dataset::parse("Shepp_Logan"), Ok(Dataset::SheppLogan));
    }

    #[test]
    fn unknown_name_lists_the_choices() {
        let e = Dataset::parse("bunny").unwrap_err().to_string();
        assert!(e.contains("'bunny'") && e.contains("shepp-logan") && e.contains("constant"), "{e}");
    }
}
