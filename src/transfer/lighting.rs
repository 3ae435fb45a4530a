//! Volume shading: the material (vtkVolumeProperty's Ambient, Diffuse,
//! Specular, SpecularPower) and the lights, and VTK 9.2's shading model
//! (`vtkVolumeShaderComposer.h`, `ComputeLightingDeclaration`), applied to a
//! sample's colour `c` from the transfer function.
//!
//! `N` is the unit gradient of the field (0 where the gradient is 0: then
//! only the ambient term remains, as VTK's headlight branch does), `V` the
//! unit ray direction (eye to sample), `L` a light's unit direction of
//! travel (light to focal point), `ka, kd, ks, p` the material. With VTK's
//! *default lighting* (one headlight of intensity 1, [`Lights::Headlight`];
//! VTK takes `L` from the camera position to the ray's entry point, the ray
//! direction under perspective, so `L = V`):
//!
//! ```text
//! d = N . L,  R = 2 d N - L,  d = |d| if two-sided
//! c' = ka c + [d > 0] (kd d Ld c + ks max(R . V, 0)^p Ls)
//! ```
//!
//! with any other set of lights ([`Lights::Directional`], each colour times
//! the light's intensity; the ambient term takes the lights' ambient colours,
//! not `c`, as VTK does, so a light kit, whose lights have black ambient
//! colours, adds no ambient light):
//!
//! ```text
//! d_i = N . L_i (|d_i| if two-sided),  R_i = normalize(2 d_i N - L_i)
//! c' = ka sum La_i + kd sum [d_i > 0] d_i Ld_i c + ks sum [d_i > 0][R_i . V > 0] (R_i . V)^p Ls_i
//! ```
//!
//! and `c'` clamped to `[0, 1]` per channel; the opacity is not changed.
//! The headlight's `R` (made before the two-sided flip) is a unit vector
//! when `N` and `L` are, so it is not normalised again.

use crate::base::error::{Error, Result};
use crate::geometry::camera::Camera;
use crate::geometry::vec3::{add, dot, normalize, scale, sub};

/// vtkVolumeProperty's shading coefficients.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Material {
    /// Ambient coefficient `ka` (VTK's default 0.1).
    pub ambient: f64,
    /// Diffuse coefficient `kd` (default 0.7).
    pub diffuse: f64,
    /// Specular coefficient `ks` (default 0.2).
    pub specular: f64,
    /// Specular power `p` (default 10).
    pub specular_power: f64,
}

impl Default for Material {
    /// vtkVolumeProperty's defaults: 0.1, 0.7, 0.2, 10.
    fn default() -> Material {
        Material { ambient: 0.1, diffuse: 0.7, specular: 0.2, specular_power: 10.0 }
    }
}

/// The frame a light's direction is given in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LightSpace {
    /// World coordinates (scene lights).
    World,
    /// View coordinates, VTK's eye frame: x right, y up, z towards the
    /// viewer (camera lights, the light kit's key, fill, back and head lights).
    View,
}

/// A directional light.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Light {
    /// Direction of travel (light to focal point), any non-zero length.
    pub direction: [f64; 3],
    /// The frame of `direction`.
    pub space: LightSpace,
    /// Ambient colour times intensity.
    pub ambient: [f64; 3],
    /// Diffuse colour times intensity.
    pub diffuse: [f64; 3],
    /// Specular colour times intensity.
    pub specular: [f64; 3],
}

/// The lights (see the module documentation for the two models).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Lights {
    /// VTK's default lighting: one headlight of intensity 1, with its
    /// diffuse and specular colours.
    Headlight {
        /// Diffuse colour `Ld`.
        diffuse: [f64; 3],
        /// Specular colour `Ls`.
        specular: [f64; 3],
    },
    /// Any other set of directional lights.
    Directional(Vec<Light>),
}

/// Material, lights and two-sided lighting: what shading needs besides the normal.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Lighting {
    /// The material.
    pub material: Material,
    /// The lights.
    pub lights: Lights,
    /// vtkRenderer's TwoSidedLighting (default on).
    pub two_sided: bool,
}

impl Lighting {
    /// A white headlight with `material`, two-sided: VTK's default lighting.
    pub fn headlight(material: Material) -> Lighting {
        Lighting { material, lights: Lights::Headlight { diffuse: [1.0; 3], specular: [1.0; 3] }, two_sided: true }
    }

    /// Checks every number: finite coefficients `>= 0`, a power `>= 0`,
    /// finite colours `>= 0`, non-zero finite light directions.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] naming the first bad value.
    pub fn check(&self) -> Result<()> {
        let m = &self.material;
        for (name, v) in [
            ("ambient", m.ambient),
            ("diffuse", m.diffuse),
            ("specular", m.specular),
            ("specular power", m.specular_power),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::InvalidArgument(format!("shading: {name} {v}: give a finite number of at least 0")));
            }
        }
        let colour = |what: &str, c: [f64; 3]| {
            if c.iter().all(|v| v.is_finite() && *v >= 0.0) {
                Ok(())
            } else {
                Err(Error::InvalidArgument(format!("shading: light {what} colour {c:?}: give finite values >= 0")))
            }
        };
        match &self.lights {
            Lights::Headlight { diffuse, specular } => {
                colour("diffuse", *diffuse)?;
                colour("specular", *specular)?;
            }
            Lights::Directional(lights) => {
                for l in lights {
                    colour("ambient", l.ambient)?;
                    colour("diffuse", l.diffuse)?;
                    colour("specular", l.specular)?;
                    if !l.direction.iter().all(|v| v.is_finite()) || l.direction.iter().all(|&v| v == 0.0) {
                        return Err(Error::InvalidArgument(format!(
                            "shading: light direction {:?}: give a finite, non-zero direction",
                            l.direction
                        )));
                    }
                }
            }
        }
        Ok(())
    }

    /// True when shading gives every colour back unchanged, so the planner
    /// draws the volume unshaded and no gradient is computed: `kd = ks = 0`
    /// and the ambient factor is 1 (`ka = 1` with the headlight; `ka sum
    /// La_i = c` cannot hold for every `c` with directional lights).
    pub fn is_identity(&self) -> bool {
        let m = &self.material;
        m.diffuse == 0.0 && m.specular == 0.0 && m.ambient == 1.0 && matches!(self.lights, Lights::Headlight { .. })
    }

    /// The same lighting with every light's direction in world space, made
    /// unit, for `camera` (view `(x, y, z)` is `x right + y up - z forward`).
    pub fn in_world(&self, camera: &Camera) -> Lighting {
        let (right, up, forward) = camera.basis();
        let lights = match &self.lights {
            Lights::Headlight { .. } => self.lights.clone(),
            Lights::Directional(lights) => Lights::Directional(
                lights
                    .iter()
                    .map(|l| {
                        let d = l.direction;
                        let world = match l.space {
                            LightSpace::World => d,
                            LightSpace::View => [0, 1, 2].map(|a| d[0] * right[a] + d[1] * up[a] - d[2] * forward[a]),
                        };
                        Light { direction: normalize(world), space: LightSpace::World, ..*l }
                    })
                    .collect(),
            ),
        };
        Lighting { lights, ..self.clone() }
    }

    /// The headlight's shading prepared for many samples ([`Headlit`]);
    /// `None` with directional lights.
    pub(crate) fn headlit(&self) -> Option<Headlit> {
        let m = &self.material;
        match &self.lights {
            Lights::Headlight { diffuse, specular } => Some(Headlit {
                ambient: m.ambient,
                diffuse: diffuse.map(|l| m.diffuse * l),
                specular: specular.map(|l| m.specular * l),
                power: SpecularPower::of(m.specular_power),
                glossy: m.specular > 0.0,
                two_sided: self.two_sided,
            }),
            Lights::Directional(_) => None,
        }
    }

    /// The shaded colour `c'` of straight colour `c` at unit normal `n` (or
    /// 0) seen along unit `view` (module documentation); light directions
    /// must be in world space and unit ([`Self::in_world`]).
    pub fn shade(&self, c: [f64; 3], n: [f64; 3], view: [f64; 3]) -> [f64; 3] {
        self.shade_unclamped(c, n, view).map(|v| v.clamp(0.0, 1.0))
    }

    /// [`Self::shade`] before the clamp to `[0, 1]` (VTK's `finalColor`,
    /// which volumetric scattering blends before clamping).
    pub fn shade_unclamped(&self, c: [f64; 3], n: [f64; 3], view: [f64; 3]) -> [f64; 3] {
        let m = &self.material;
        let mut out = [0.0; 3];
        match &self.lights {
            Lights::Headlight { diffuse, specular } => {
                let l = view;
                let mut d = dot(n, l);
                let r = sub(scale(n, 2.0 * d), l);
                let rv = dot(r, view).max(0.0);
                if d < 0.0 && self.two_sided {
                    d = -d;
                }
                let lit = d > 0.0;
                let sf = if lit && m.specular > 0.0 { specular_factor(rv, m.specular_power) } else { 0.0 };
                for a in 0..3 {
                    out[a] = m.ambient * c[a];
                    if lit {
                        out[a] += m.diffuse * d * diffuse[a] * c[a] + m.specular * sf * specular[a];
                    }
                }
            }
            Lights::Directional(lights) => {
                let (mut amb, mut dif, mut spe) = ([0.0; 3], [0.0; 3], [0.0; 3]);
                for light in lights {
                    let l = light.direction;
                    let mut d = dot(n, l);
                    if d < 0.0 && self.two_sided {
                        d = -d;
                    }
                    if d > 0.0 {
                        // Not unit when two-sided lighting flipped d: normalised, as VTK does.
                        let r = normalize(sub(scale(n, 2.0 * d), l));
                        let rv = dot(r, view);
                        let sf = if rv > 0.0 && m.specular > 0.0 { specular_factor(rv, m.specular_power) } else { 0.0 };
                        for a in 0..3 {
                            dif[a] += d * light.diffuse[a];
                            spe[a] += sf * light.specular[a];
                        }
                    }
                    amb = add(amb, light.ambient);
                }
                for a in 0..3 {
                    out[a] = m.ambient * amb[a] + m.diffuse * dif[a] * c[a] + m.specular * spe[a];
                }
            }
        }
        out
    }
}

/// The specular factor `(r . v)^s` of the Phong model, `rv = r . v >= 0`
/// and `s` the specular power ([`SpecularPower`]).
#[inline]
fn specular_factor(rv: f64, s: f64) -> f64 {
    SpecularPower::of(s).raise(rv)
}

/// A specular power `s`, classified once: a whole number up to 128 (VTK's
/// default 10, ParaView's 100) is taken by repeated squaring, a fraction of
/// the cost of `powf` and equal to it within a few ulps; any other by `powf`.
#[derive(Debug, Clone, Copy, PartialEq)]
enum SpecularPower {
    Whole(u32),
    Real(f64),
}

impl SpecularPower {
    fn of(s: f64) -> SpecularPower {
        if s.fract() == 0.0 && (0.0..=128.0).contains(&s) {
            SpecularPower::Whole(s as u32)
        } else {
            SpecularPower::Real(s)
        }
    }

    /// `x^s`: for a whole `s`, the product of `x^(2^k)` over the bits `k`
    /// of `s` (the multiplications of `powi`, inlined).
    #[inline(always)]
    fn raise(self, x: f64) -> f64 {
        match self {
            SpecularPower::Whole(mut n) => {
                let (mut r, mut x) = (1.0, x);
                while n > 0 {
                    if n & 1 == 1 {
                        r *= x;
                    }
                    x *= x;
                    n >>= 1;
                }
                r
            }
            SpecularPower::Real(s) => x.powf(s),
        }
    }
}

/// The headlight's shading ([`Lights::Headlight`]) prepared for the many
/// samples of a frame, taking each sample's gradient `g` as it comes: the
/// coefficients multiplied out and the specular power classified once. With
/// `N = g / |g|` and `L = V` (unit), `R = 2 d N - V` gives `R . V = 2 d^2 - 1`,
/// so no normal and no reflection vector is made:
///
/// ```text
/// d  = (g . V) / |g|   (0 when |g|^2 is 0 or not finite: ambient only)
/// d' = |d| if two-sided, else d
/// c' = ka c + [d' > 0] (kd Ld d' c + ks Ls max(2 d^2 - 1, 0)^p)
/// ```
///
/// clamped to `[0, 1]`: [`Lighting::shade`]'s value up to rounding.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Headlit {
    /// `ka`.
    ambient: f64,
    /// `kd Ld`, per channel.
    diffuse: [f64; 3],
    /// `ks Ls`, per channel.
    specular: [f64; 3],
    /// `p`.
    power: SpecularPower,
    /// `ks > 0`: the specular power is taken.
    glossy: bool,
    two_sided: bool,
}

impl Headlit {
    /// The shaded colour `c'` of straight colour `c` at gradient `g` (any
    /// length, or 0) seen along unit `view`.
    #[inline(always)]
    pub(crate) fn shade(&self, c: [f64; 3], g: [f64; 3], view: [f64; 3]) -> [f64; 3] {
        let mut out = [self.ambient * c[0], self.ambient * c[1], self.ambient * c[2]];
        let gg = dot(g, g);
        if gg > 0.0 && gg.is_finite() {
            let d = dot(g, view) / gg.sqrt();
            let rv = (2.0 * d * d - 1.0).max(0.0);
            let d = if self.two_sided { d.abs() } else { d };
            if d > 0.0 {
                let sf = if self.glossy { self.power.raise(rv) } else { 0.0 };
                for a in 0..3 {
                    out[a] += self.diffuse[a] * d * c[a] + self.specular[a] * sf;
                }
            }
        }
        [out[0].clamp(0.0, 1.0), out[1].clamp(0.0, 1.0), out[2].clamp(0.0, 1.0)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `g / |g|`, or 0 (the renderers' normal).
    fn normal(g: [f64; 3]) -> [f64; 3] {
        let l = dot(g, g).sqrt();
        if l > 0.0 && l.is_finite() {
            g.map(|v| v / l)
        } else {
            [0.0; 3]
        }
    }

    fn kit() -> Lighting {
        let light =
            |direction, space| Light { direction, space, ambient: [0.0; 3], diffuse: [0.5; 3], specular: [1.0; 3] };
        Lighting {
            material: Material::default(),
            lights: Lights::Directional(vec![
                light([0.0, 0.0, -1.0], LightSpace::View),
                light([1.0, 0.0, 0.0], LightSpace::World),
            ]),
            two_sided: true,
        }
    }

    /// The specular factor by multiplication is `powf`'s within 1e-12 for
    /// whole powers, and `powf` itself for fractional ones.
    #[test]
    fn specular_factor_matches_powf() {
        for s in [0.0, 1.0, 2.0, 10.0, 100.0, 128.0, 2.5, 129.0, 0.3] {
            for k in 0..=100 {
                let rv = f64::from(k) / 100.0;
                let (a, b) = (specular_factor(rv, s), rv.powf(s));
                assert!((a - b).abs() <= 1e-12 * b.max(1e-300) + 1e-300, "{rv}^{s}: {a} vs {b}");
            }
        }
    }

    /// The prepared headlight from a gradient of any length is the textbook
    /// one at its normal within 1e-12, for one- and two-sided lighting, whole,
    /// zero and fractional powers, coloured lights, and zero or overflowing
    /// gradients (ambient only).
    #[test]
    fn headlit_is_shade_at_the_normal() {
        let materials = [
            Material::default(),
            Material { ambient: 0.3, diffuse: 0.5, specular: 0.9, specular_power: 0.0 },
            Material { ambient: 0.0, diffuse: 1.0, specular: 0.6, specular_power: 37.5 },
            Material { ambient: 0.2, diffuse: 0.4, specular: 0.0, specular_power: 100.0 },
        ];
        let mut checked = 0;
        for material in materials {
            for two_sided in [true, false] {
                let lights = Lights::Headlight { diffuse: [1.0, 0.5, 0.8], specular: [0.9, 1.0, 0.3] };
                let l = Lighting { material, lights, two_sided };
                let h = l.headlit().unwrap();
                let view = normalize([0.3, -0.5, -0.8]);
                for k in 0..400 {
                    let f = f64::from(k);
                    let g = [(f * 0.37).sin(), (f * 0.73).cos(), (f * 0.11).sin() - 0.5]
                        .map(|v| v * 10f64.powf(f / 40.0 - 5.0));
                    let c = [0.9, (f * 0.05).fract(), 0.25];
                    let (fast, textbook) = (h.shade(c, g, view), l.shade(c, normal(g), view));
                    for a in 0..3 {
                        assert!((fast[a] - textbook[a]).abs() < 1e-12, "{material:?} {g:?}: {fast:?} vs {textbook:?}");
                    }
                    checked += 1;
                }
                for g in [[0.0; 3], [1e200, 0.0, 0.0], [f64::NAN, 0.0, 1.0]] {
                    assert_eq!(h.shade([0.5; 3], g, view), [0.5 * material.ambient; 3]);
                }
            }
        }
        assert_eq!(checked, 3200);
        assert!(kit().headlit().is_none());
    }

    /// The headlight on a normal facing the viewer: `ka c + kd c + ks`; at
    /// grazing light only the ambient term; a zero normal: ambient only.
    #[test]
    fn headlight_terms() {
        let l = Lighting::headlight(Material::default());
        let v = [0.0, 0.0, -1.0];
        let c = [0.5, 0.25, 1.0];
        let lit = l.shade(c, [0.0, 0.0, -1.0], v);
        for a in 0..3 {
            assert!((lit[a] - (0.1 * c[a] + 0.7 * c[a] + 0.2).min(1.0)).abs() < 1e-12, "{lit:?}");
        }
        // Two-sided: the opposite normal is lit the same.
        assert_eq!(l.shade(c, [0.0, 0.0, 1.0], v), lit);
        assert_eq!(l.shade(c, [1.0, 0.0, 0.0], v), c.map(|x| 0.1 * x));
        assert_eq!(l.shade(c, [0.0; 3], v), c.map(|x| 0.1 * x));
        let one_sided = Lighting { two_sided: false, ..l.clone() };
        assert_eq!(one_sided.shade(c, [0.0, 0.0, 1.0], v), c.map(|x| 0.1 * x));
        assert!(Lighting::headlight(Material { ambient: 1.0, diffuse: 0.0, specular: 0.0, specular_power: 3.0 })
            .is_identity());
        assert!(!l.is_identity() && !kit().is_identity());
    }

    /// Directional lights: view-space directions turned to world by the
    /// camera; ambient from the lights' ambient colours (black here).
    #[test]
    fn directional_lights_in_world() {
        let camera = Camera::new(
            [0.0, 0.0, 10.0],
            [0.0; 3],
            [0.0, 1.0, 0.0],
            crate::geometry::camera::Projection::Parallel { scale: 1.0 },
        )
        .unwrap();
        let w = kit().in_world(&camera);
        let Lights::Directional(lights) = &w.lights else { panic!() };
        // View -z is the camera's forward, world -z here.
        assert!((lights[0].direction[2] + 1.0).abs() < 1e-12);
        let c = [1.0, 0.5, 0.0];
        let out = w.shade(c, [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]);
        // Light 0: d = 1, R = (0, 0, 1)... R . V = -1 -> no specular; light 1: d = 0.
        for a in 0..3 {
            assert!((out[a] - 0.7 * 0.5 * c[a]).abs() < 1e-12, "{out:?}");
        }
        assert!(kit().check().is_ok());
        let mut bad = kit();
        bad.material.diffuse = f64::NAN;
        assert!(bad.check().unwrap_err().to_string().contains("diffuse"));
    }
}
