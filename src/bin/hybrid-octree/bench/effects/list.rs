//! The effects `bench effects` measures: a table of named scene modifiers.
//! Each entry turns its effect on in the scene arguments of a plain
//! composite frame (no shading, Composite, no surface); a new effect is one
//! more line in [`EFFECTS`] (its `SceneArgs` field set by the modifier).

use crate::scene::SceneArgs;
use hybrid_octree::plan::BlendMode;

/// What a modifier may read of the data and the command line (a new
/// effect that needs more, e.g. the data's bounds, adds a field here and
/// fills it in `super::context`).
#[derive(Debug, Clone, Copy)]
pub struct Context {
    /// The isovalue of the surface rows: `--isovalue`, else the middle of the range.
    pub isovalue: f64,
    /// The opacity of the translucent surface rows: `--surface-opacity` when
    /// below 1, else [`TRANSLUCENT`].
    pub translucent_opacity: f64,
    /// The world box of the grid's samples (lowest corner, highest corner):
    /// where the cropping and clipping rows cut.
    pub bounds: ([f64; 3], [f64; 3]),
    /// The octree's value range (lowest, highest).
    pub value_range: (f64, f64),
    /// The mean sample spacing (world units): gradient magnitudes scale with it.
    pub spacing: f64,
}

/// A named change of the scene: one row of the table.
pub struct Effect {
    /// The row's name (`--effects` picks rows by it).
    pub name: &'static str,
    /// Turns the effect on in a plain scene's arguments.
    pub apply: fn(&mut SceneArgs, &Context),
}

/// The translucent surface's default opacity.
pub const TRANSLUCENT: f64 = 0.4;

/// The plain composite frame every other row is measured against (the first row).
pub const PLAIN: &str = "plain";

/// Every effect, the plain frame first.
pub const EFFECTS: &[Effect] = &[
    Effect { name: PLAIN, apply: |_, _| {} },
    Effect { name: "shade", apply: |s, _| s.shade.shade = true },
    Effect { name: "shade+specular", apply: |s, _| specular(s) },
    Effect { name: "mip", apply: |s, _| s.blend = BlendMode::Mip },
    Effect { name: "minip", apply: |s, _| s.blend = BlendMode::Minip },
    Effect { name: "average", apply: |s, _| s.blend = BlendMode::Average },
    Effect { name: "additive", apply: |s, _| s.blend = BlendMode::Additive },
    Effect { name: "translucent-iso", apply: translucent_surface },
    Effect { name: "shade+translucent-iso", apply: shaded_translucent_surface },
    Effect { name: "gradient-opacity", apply: gradient_opacity },
    Effect {
        name: "shade+gradient-opacity",
        apply: |s, c| {
            s.shade.shade = true;
            gradient_opacity(s, c)
        },
    },
    Effect { name: "isosurface", apply: isosurfaces },
    Effect {
        name: "shade+isosurface",
        apply: |s, c| {
            s.shade.shade = true;
            isosurfaces(s, c)
        },
    },
    Effect { name: "cropping", apply: |s, c| s.crop.crop = Some(central_box(c)) },
    Effect { name: "clipping", apply: |s, c| s.crop.clip = vec![oblique_plane(c)] },
    Effect { name: "scattering", apply: |s, _| scattering(s, 0.5) },
    Effect { name: "scattering-full-reach", apply: |s, _| scattering(s, 1.0) },
];

/// Shading with volumetric scattering: blending 1 (VTK's blend of the two
/// models), anisotropy 0.3, the shadow rays' reach `reach` (1: across the
/// whole volume, at most the step cap).
fn scattering(s: &mut SceneArgs, reach: f64) {
    s.shade.shade = true;
    s.scattering.scatter_blending = 1.0;
    s.scattering.scatter_reach = reach;
    s.scattering.scatter_anisotropy = 0.3;
}

/// Shading with a strong, tight highlight (specular 0.8, power 40) over the
/// ambient and diffuse of `--ambient` and `--diffuse`.
fn specular(s: &mut SceneArgs) {
    s.shade.shade = true;
    s.shade.specular = 0.8;
    s.shade.specular_power = 40.0;
}

/// The isosurface at the context's isovalue and translucent opacity, drawn in the slabs.
fn translucent_surface(s: &mut SceneArgs, c: &Context) {
    s.isovalue = Some(c.isovalue);
    s.surface_opacity = c.translucent_opacity;
}

/// Shading (VTK's default material) with the translucent isosurface.
fn shaded_translucent_surface(s: &mut SceneArgs, c: &Context) {
    s.shade.shade = true;
    translucent_surface(s, c);
}

/// Gradient opacity rising from 0 at magnitude 0 to 1 where the value
/// changes by a tenth of its range per sample spacing: flat regions fade,
/// boundaries stay.
fn gradient_opacity(s: &mut SceneArgs, c: &Context) {
    let (lo, hi) = c.value_range;
    let full = 0.1 * (hi - lo).max(f64::MIN_POSITIVE) / c.spacing;
    s.gradient_opacity = hybrid_octree::transfer::GradientOpacity::new(vec![(0.0, 0.0), (full, 1.0)]).ok();
}

/// The Isosurface blend mode at a third and two thirds of the value range.
fn isosurfaces(s: &mut SceneArgs, c: &Context) {
    let (lo, hi) = c.value_range;
    s.blend = BlendMode::Isosurface;
    s.isosurface_values = vec![lo + (hi - lo) / 3.0, lo + 2.0 * (hi - lo) / 3.0];
}

/// The cropping box of the cropping row: VTK's subvolume keeping the middle
/// half of each axis of the bounds, off centre (from 20 % to 70 %).
fn central_box(c: &Context) -> [f64; 6] {
    let (lo, hi) = c.bounds;
    let at = |a: usize, f: f64| lo[a] + f * (hi[a] - lo[a]);
    [at(0, 0.2), at(0, 0.7), at(1, 0.2), at(1, 0.7), at(2, 0.2), at(2, 0.7)]
}

/// The clipping row's plane: through the bounds' centre, oblique, keeping
/// the half its normal `(1, -0.6, 0.4)` points to.
fn oblique_plane(c: &Context) -> hybrid_octree::plan::crop::ClippingPlane {
    let (lo, hi) = c.bounds;
    hybrid_octree::plan::crop::ClippingPlane {
        origin: [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a])),
        normal: [1.0, -0.6, 0.4],
    }
}

/// The effects named in `names` (all when empty), in the table's order, the plain frame always first.
pub fn chosen(names: &[String]) -> Result<Vec<&'static Effect>, String> {
    if let Some(unknown) = names.iter().find(|n| !EFFECTS.iter().any(|e| e.name == n.as_str())) {
        let known: Vec<&str> = EFFECTS.iter().map(|e| e.name).collect();
        return Err(format!("unknown effect '{unknown}': choose from {}", known.join(", ")));
    }
    Ok(EFFECTS.iter().filter(|e| e.name == PLAIN || names.is_empty() || names.iter().any(|n| n == e.name)).collect())
}
