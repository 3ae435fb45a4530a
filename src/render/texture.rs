//! The "upload": every brick's texture copied once into its own contiguous
//! array, as a GPU slicer uploads 3D textures before it draws.
//!
//! Texel `(i, j, k)` of a brick of `n` texels per axis is stored at
//! `i + n_x (j + n_y k)` and holds the grid value at the texel position
//! `min(lo + (i, j, k) stride, hi)` (see [`crate::plan::select::Brick::texel_positions`]).
//! The copy is `f32` when every copied value is exactly an `f32` (all `u8`,
//! `i8`, `u16`, `i16` and `f32` grids), else `f64`: either way it holds the
//! grid's values exactly, and `Texture::value` reconstructs T_p bit for bit
//! (the trilinear formula and evaluation order of `render::sample`):
//!
//! ```text
//! u = (x - lo) / stride,  clamped to [0, n - 1];  i0 = floor(u), i1 = min(i0 + 1, n - 1), t = u - i0
//! v(ia, jb) = lerp(f(ia, jb, k0), f(ia, jb, k1), tz),  w(ia) = lerp(v(ia, j0), v(ia, j1), ty)
//! T_p(x)    = lerp(w(i0), w(i1), tx)
//! ```
//!
//! A coarse brick of a maximum (minimum) intensity picture holds instead
//! the largest (smallest) grid value within a stride of each texel
//! position, so that it never hides a peak (`pool`).
//!
//! Textures are made once per DrawList, bricks in parallel; a frame reads
//! only them, never the grid.

use super::check::check_bricks;
use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridShape, GridVisitor, Sample, TypedGrid};
use crate::octree::trilinear::lerp;
use crate::plan::select::Brick;
use crate::plan::texel_format::TexelFormat;
use crate::plan::{BlendMode, DrawList};
use rayon::prelude::*;

pub mod encoded;
pub(crate) mod gradient;
mod pool;
pub mod read;

/// A stored texel: `f32` or `f64` holding the value, or the `u8` or `u16`
/// code of a normalized texel format ([`crate::plan::texel_format::TexelEncoding`]), read back as `f64`.
pub(crate) trait Texel: Copy + Send + Sync + 'static {
    /// A code, decoded after interpolation: `value = bias + step * code`
    /// ([`Texture::at_texel`]); a float texel is the value itself.
    const CODED: bool = false;
    /// The texel holding `v`, `None` when `v` is not exactly representable.
    fn exact(v: f64) -> Option<Self>;
    /// The stored value (or code).
    fn get(self) -> f64;
}

impl Texel for u8 {
    const CODED: bool = true;
    #[inline]
    fn exact(v: f64) -> Option<u8> {
        (v.fract() == 0.0 && (0.0..=255.0).contains(&v)).then_some(v as u8)
    }
    #[inline(always)]
    fn get(self) -> f64 {
        f64::from(self)
    }
}

/// The half float `t` of [`TexelFormat::Float16`], decoded `bias + scale t`.
impl Texel for half::f16 {
    const CODED: bool = true;
    #[inline]
    fn exact(v: f64) -> Option<half::f16> {
        let t = half::f16::from_f64(v);
        (t.to_f64() == v).then_some(t)
    }
    #[inline(always)]
    fn get(self) -> f64 {
        self.to_f64()
    }
}

impl Texel for u16 {
    const CODED: bool = true;
    #[inline]
    fn exact(v: f64) -> Option<u16> {
        (v.fract() == 0.0 && (0.0..=65535.0).contains(&v)).then_some(v as u16)
    }
    #[inline(always)]
    fn get(self) -> f64 {
        f64::from(self)
    }
}

impl Texel for f32 {
    #[inline]
    fn exact(v: f64) -> Option<f32> {
        let t = v as f32;
        (t as f64 == v).then_some(t)
    }
    #[inline(always)]
    fn get(self) -> f64 {
        self as f64
    }
}

impl Texel for f64 {
    #[inline]
    fn exact(v: f64) -> Option<f64> {
        Some(v)
    }
    #[inline(always)]
    fn get(self) -> f64 {
        self
    }
}

/// The grid values at `brick`'s texel positions, texel `(i, j, k)` at
/// `i + n_x (j + n_y k)` (x fastest), each stored by `f`; `None` at the first
/// value `f` refuses. The one texel layout of every brick texture (the
/// uploads here and the bridge's `brick_texels`); the brick must lie in the grid.
/// With a `border` of 1 (the plan takes gradients: shading, gradient
/// opacity), one more texel on each side: texel `i` of `n + 2` at
/// `lo + (i - 1) stride`, clamped to the grid (see [`bordered_position`]).
fn texel_values<T: Sample, S>(
    g: &TypedGrid<'_, T>,
    brick: &Brick,
    border: usize,
    f: impl Fn(f64) -> Option<S>,
) -> Option<Vec<S>> {
    let pos = |a: usize, i: usize| {
        if border == 0 {
            (brick.lo[a] + i * brick.stride).min(brick.hi[a])
        } else {
            bordered_position(brick, g.dims, a, i)
        }
    };
    let n = brick.texels.map(|n| n + 2 * border);
    let mut data = Vec::with_capacity(n[0] * n[1] * n[2]);
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                data.push(f(g.at(pos(0, i), pos(1, j), pos(2, k)))?);
            }
        }
    }
    Some(data)
}

/// Grid index of texel `i` (of `n + 2`) along `axis` of `brick`'s texture
/// with a gradient border:
///
/// ```text
/// position(i) = clamp(lo + (i - 1) stride, 0, dims - 1)
/// ```
///
/// Texels `1 ..= n` are the brick's own (`min(lo + i stride, hi)`: `hi` is
/// on the brick's lattice or the grid's last sample), texels 0 and `n + 1`
/// the neighbours one stride outside, which the central differences at the
/// brick's faces read, so a brick's gradient there is its neighbour's at
/// the same stride (no seam); at the grid's faces they repeat its last
/// sample, as the full-resolution reconstruction clamps.
pub fn bordered_position(brick: &Brick, dims: [usize; 3], axis: usize, i: usize) -> usize {
    (brick.lo[axis] + i * brick.stride).saturating_sub(brick.stride).min(dims[axis] - 1)
}

/// One brick's texels as `f32`, in the layout of the module documentation
/// (x fastest, texel positions `min(lo + i stride, hi)`): what a GPU
/// executor uploads as a 3D texture. Values are rounded to the nearest `f32`:
/// exact for `u8`, `i8`, `u16`, `i16` and `f32` grids; `f64` values and `u32`
/// or `i32` values beyond 2^24 in magnitude lose their low bits.
///
/// # Errors
///
/// [`Error::InvalidArgument`] if the brick is not a brick of this grid (its
/// box outside the grid, a zero stride or texel counts that do not match).
pub fn brick_texels_f32(grid: &Grid<'_>, brick: &Brick) -> Result<Vec<f32>> {
    let mut texels = vec![0.0; texel_count(grid, brick)?];
    brick_texels_f32_into(grid, brick, &mut texels)?;
    Ok(texels)
}

/// The texel count of `brick`, checked to be a brick of `grid`.
fn texel_count(grid: &Grid<'_>, brick: &Brick) -> Result<usize> {
    let dims = grid.dims();
    let expected = [0, 1, 2].map(|a| (brick.hi[a].saturating_sub(brick.lo[a])).div_ceil(brick.stride.max(1)) + 1);
    if brick.stride == 0
        || (0..3).any(|a| brick.lo[a] > brick.hi[a] || brick.hi[a] >= dims[a])
        || brick.texels != expected
    {
        return Err(Error::InvalidArgument(format!(
            "brick (node {}) has box {:?}..{:?}, stride {} and texels {:?}: not a brick of this {dims:?} grid",
            brick.node.0, brick.lo, brick.hi, brick.stride, brick.texels
        )));
    }
    Ok(brick.texels.iter().product())
}

/// [`brick_texels_f32`] into `texels`, the caller's buffer of the brick's
/// texel count (e.g. a GPU upload's staging memory).
///
/// # Errors
///
/// As [`brick_texels_f32`], and [`Error::InvalidArgument`] if `texels` does
/// not hold the brick's texel count.
pub fn brick_texels_f32_into(grid: &Grid<'_>, brick: &Brick, texels: &mut [f32]) -> Result<()> {
    texels_f32_into(grid, brick, 0, texels)
}

/// [`brick_texels_f32_into`] with the gradient border of a shaded volume:
/// `(n + 2)` texels per axis, texel `i` at [`bordered_position`].
///
/// # Errors
///
/// As [`brick_texels_f32_into`], the buffer holding `(n_x + 2) (n_y + 2) (n_z + 2)` texels.
pub fn brick_texels_f32_bordered_into(grid: &Grid<'_>, brick: &Brick, texels: &mut [f32]) -> Result<()> {
    texels_f32_into(grid, brick, 1, texels)
}

/// The brick's texels as `f32` with `border` texels per side (0 or 1).
fn texels_f32_into(grid: &Grid<'_>, brick: &Brick, border: usize, texels: &mut [f32]) -> Result<()> {
    texel_count(grid, brick)?;
    let count = brick.texels.iter().map(|n| n + 2 * border).product::<usize>();
    if texels.len() != count {
        return Err(Error::InvalidArgument(format!(
            "a buffer of {} texels for brick (node {}) of {count} texels",
            texels.len(),
            brick.node.0
        )));
    }
    struct F32<'b, 't>(&'b Brick, usize, &'t mut [f32]);
    impl GridVisitor for F32<'_, '_> {
        type Output = ();
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) {
            let F32(brick, border, texels) = self;
            let pos = |a: usize, i: usize| {
                if border == 0 {
                    (brick.lo[a] + i * brick.stride).min(brick.hi[a])
                } else {
                    bordered_position(brick, g.dims, a, i)
                }
            };
            let n = brick.texels.map(|n| n + 2 * border);
            let mut to = texels.iter_mut();
            for k in 0..n[2] {
                for j in 0..n[1] {
                    for i in 0..n[0] {
                        // The buffer holds exactly n[0] n[1] n[2] texels (checked above).
                        if let Some(t) = to.next() {
                            *t = g.at(pos(0, i), pos(1, j), pos(2, k)) as f32;
                        }
                    }
                }
            }
        }
    }
    grid.visit(F32(brick, border, texels));
    Ok(())
}

/// [`brick_texels_f32_into`] for a picture of blend mode `mode`: a coarse
/// brick (stride > 1) of a MIP or MinIP gets its peak-keeping texels
/// (`pool`), every other brick its plain ones. What a GPU executor of a
/// maximum or minimum intensity DrawList uploads.
///
/// # Errors
///
/// As [`brick_texels_f32_into`].
pub fn brick_texels_for_blend_f32_into(
    grid: &Grid<'_>,
    brick: &Brick,
    mode: BlendMode,
    texels: &mut [f32],
) -> Result<()> {
    if !(mode.is_extremum() && brick.stride > 1) {
        return brick_texels_f32_into(grid, brick, texels);
    }
    let count = texel_count(grid, brick)?;
    if texels.len() != count {
        return Err(Error::InvalidArgument(format!(
            "a buffer of {} texels for brick (node {}) of {count} texels",
            texels.len(),
            brick.node.0
        )));
    }
    struct Pooled<'b, 't>(&'b Brick, bool, &'t mut [f32]);
    impl GridVisitor for Pooled<'_, '_> {
        type Output = ();
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) {
            let Pooled(brick, largest, texels) = self;
            if let Some(values) = pool::pooled_values(&g, brick, largest, |v| Some(v as f32)) {
                texels.copy_from_slice(&values);
            }
        }
    }
    grid.visit(Pooled(brick, mode == BlendMode::Mip, texels));
    Ok(())
}

/// One brick's texture: its texels, contiguous, x fastest.
#[derive(Debug, Clone)]
pub(crate) struct Texture<S> {
    /// The brick's index box and stride (to check the texture against a DrawList).
    lo: [usize; 3],
    hi: [usize; 3],
    stride: usize,
    /// Texels per axis, the border included.
    n: [usize; 3],
    /// Border texels per side: 0, or 1 when the plan takes gradients ([`bordered_position`]).
    border: usize,
    /// `n - 1`, per axis.
    last: [f64; 3],
    data: Vec<S>,
    /// The decoding of a coded texel (`value = bias + step * code`; 1 and 0
    /// for float texels): `step = scale / L` of the [`crate::plan::texel_format::TexelEncoding`].
    step: f64,
    bias: f64,
    /// With gradients, the CPU compositor's lattice differences
    /// ([`Self::lattice_differences`]): not texture bytes a GPU holds,
    /// the executor's working memory (empty otherwise).
    lattice: Vec<[f32; 3]>,
    /// Every lattice difference is finite, so their interpolation needs no
    /// overflow test (true without differences).
    lattice_finite: bool,
}

impl<S: Texel> Texture<S> {
    /// Copies `brick`'s texels from `g` (the brick checked to lie in the grid);
    /// `None` when a value is not exactly an `S`.
    #[cfg(test)]
    fn copy<T: Sample>(g: &TypedGrid<'_, T>, brick: &Brick, border: usize) -> Option<Texture<S>> {
        Texture::copy_for(g, brick, border, BlendMode::Composite)
    }

    /// [`Self::copy`] for a picture of blend mode `mode`: a coarse brick of a
    /// MIP or MinIP holds its peak-keeping texels (`pool`); those modes are
    /// not shaded, so they have no gradient border.
    #[cfg(test)]
    fn copy_for<T: Sample>(g: &TypedGrid<'_, T>, brick: &Brick, border: usize, mode: BlendMode) -> Option<Texture<S>> {
        Texture::coded(g, brick, border, mode, S::exact, (1.0, 0.0))
    }

    /// [`Self::copy_for`] with each value stored by `f` (its code in a texel
    /// format, decoded by `(step, bias)`).
    fn coded<T: Sample>(
        g: &TypedGrid<'_, T>,
        brick: &Brick,
        border: usize,
        mode: BlendMode,
        f: impl Fn(f64) -> Option<S>,
        (step, bias): (f64, f64),
    ) -> Option<Texture<S>> {
        let data = match mode {
            BlendMode::Mip | BlendMode::Minip if brick.stride > 1 && border == 0 => {
                pool::pooled_values(g, brick, mode == BlendMode::Mip, f)?
            }
            _ => texel_values(g, brick, border, f)?,
        };
        let n = brick.texels.map(|n| n + 2 * border);
        let (lo, hi, stride, last) = (brick.lo, brick.hi, brick.stride, n.map(|n| (n - 1) as f64));
        Some(Texture { lo, hi, stride, n, border, last, data, step, bias, lattice: Vec::new(), lattice_finite: true })
    }

    /// [`Self::coded`], with the [`Self::lattice_differences`] when the
    /// plan takes `gradients`.
    fn prepared<T: Sample>(
        g: &TypedGrid<'_, T>,
        brick: &Brick,
        (border, mode, gradients): (usize, BlendMode, bool),
        f: impl Fn(f64) -> Option<S>,
        decode: (f64, f64),
    ) -> Option<Texture<S>> {
        let mut t = Texture::coded(g, brick, border, mode, f, decode)?;
        if gradients {
            t.lattice = t.lattice_differences();
            t.lattice_finite = t.lattice.iter().flatten().all(|d| d.is_finite());
        }
        Some(t)
    }

    /// This texture's box, stride, border and lattice differences holding `data` instead.
    fn with_data<D>(&self, data: Vec<D>) -> Texture<D> {
        Texture {
            lo: self.lo,
            hi: self.hi,
            stride: self.stride,
            n: self.n,
            border: self.border,
            last: self.last,
            data,
            step: self.step,
            bias: self.bias,
            lattice: self.lattice.clone(),
            lattice_finite: self.lattice_finite,
        }
    }

    /// True when this is the texture of `brick`.
    fn is_of(&self, brick: &Brick) -> bool {
        (self.lo, self.hi, self.stride, self.n.map(|n| n - 2 * self.border))
            == (brick.lo, brick.hi, brick.stride, brick.texels)
    }

    /// `stride` as a float: texel spacing in index units.
    #[inline]
    pub(crate) fn stride(&self) -> f64 {
        self.stride as f64
    }

    /// T_p at index-space point `x` (see the module documentation): [`Self::at_texel`]
    /// of `u = (x - lo) / stride`. (The compositor reads [`Self::at_texel`] along
    /// [`Self::texel_line`].)
    #[cfg(test)]
    pub(crate) fn value(&self, x: [f64; 3]) -> f64 {
        self.at_texel([0, 1, 2].map(|a| (x[a] - self.lo[a] as f64) / self.stride as f64 + self.border as f64))
    }

    /// The texel coordinates `u(s) = a + s b` of the index-space line
    /// `x(s) = xa + s xb`: `a = (xa - lo) / stride + border`, `b = xb / stride`.
    #[inline]
    pub(crate) fn texel_line(&self, xa: [f64; 3], xb: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        let s = self.stride as f64;
        let border = self.border as f64;
        ([0, 1, 2].map(|a| (xa[a] - self.lo[a] as f64) / s + border), xb.map(|b| b / s))
    }

    /// T_p at texel coordinates `u` (`u = (x - lo) / stride`, clamped to
    /// `[0, n - 1]`; see the module documentation).
    #[inline(always)]
    pub(crate) fn at_texel(&self, u: [f64; 3]) -> f64 {
        let mut i0 = [0; 3];
        let mut step = [0; 3];
        let mut t = [0.0; 3];
        let pitch = [1, self.n[0], self.n[0] * self.n[1]];
        for a in 0..3 {
            let u = u[a].clamp(0.0, self.last[a]);
            // u in [0, n - 1] (n < 2^32): the u32 cast is floor(u), both conversions single instructions.
            let i = u as u32;
            let i0a = i as usize;
            (i0[a], step[a], t[a]) = (i0a, if i0a + 1 < self.n[a] { pitch[a] } else { 0 }, u - i as f64);
        }
        let base = i0[0] + pitch[1] * i0[1] + pitch[2] * i0[2];
        self.cell_value(base, step, t)
    }

    /// The trilinear interpolation with weights `t` of the 8 texels from
    /// offset `base`, `step` apart per axis, decoded.
    #[inline(always)]
    pub(crate) fn cell_value(&self, base: usize, step: [usize; 3], t: [f64; 3]) -> f64 {
        // The 8 texels lie in data[base ..= base + step0 + step1 + step2]: one bounds check.
        let d = &self.data[base..=base + step[0] + step[1] + step[2]];
        let r = lerp(bilinear(d, 0, step, t), bilinear(d, step[0], step, t), t[0]);
        if S::CODED {
            self.bias + self.step * r
        } else {
            r
        }
    }
}

/// The bilinear interpolation over y and z (z first) of the texels of `d`
/// from offset `o`, `step` apart per axis, with weights `t`: half of a
/// trilinear read. A function of its own, always inlined (a closure
/// here is not, and this is the compositor's inner loop).
#[inline(always)]
fn bilinear<S: Texel>(d: &[S], o: usize, step: [usize; 3], t: [f64; 3]) -> f64 {
    let v0 = lerp(d[o].get(), d[o + step[2]].get(), t[2]);
    let v1 = lerp(d[o + step[1]].get(), d[o + step[1] + step[2]].get(), t[2]);
    lerp(v0, v1, t[1])
}

/// Every brick's texture of a DrawList, in list order (see the module documentation).
#[derive(Debug, Clone)]
pub struct Textures {
    pub(crate) shape: GridShape,
    pub(crate) texels: Texels,
}

/// The textures' storage type.
#[derive(Debug, Clone)]
pub(crate) enum Texels {
    F32(Vec<Texture<f32>>),
    F64(Vec<Texture<f64>>),
    /// Codes of [`TexelFormat::Unorm8`].
    U8(Vec<Texture<u8>>),
    /// Codes of [`TexelFormat::Unorm16`].
    U16(Vec<Texture<u16>>),
    /// Half floats of [`TexelFormat::Float16`].
    F16(Vec<Texture<half::f16>>),
}

impl Textures {
    /// Bytes of texel data.
    pub fn bytes(&self) -> usize {
        match &self.texels {
            Texels::F32(t) => t.iter().map(|t| t.data.len() * 4).sum(),
            Texels::F64(t) => t.iter().map(|t| t.data.len() * 8).sum(),
            Texels::U8(t) => t.iter().map(|t| t.data.len()).sum(),
            Texels::U16(t) => t.iter().map(|t| t.data.len() * 2).sum(),
            Texels::F16(t) => t.iter().map(|t| t.data.len() * 2).sum(),
        }
    }

    /// The same textures stored as `f64` values (exact: every `f32` is an
    /// `f64`, a code's decoded value is computed in `f64`).
    pub(crate) fn widened(self) -> Textures {
        fn wide<S: Texel>(t: &[Texture<S>]) -> Vec<Texture<f64>> {
            t.iter()
                .map(|t| {
                    let decode = |v: S| if S::CODED { t.bias + t.step * v.get() } else { v.get() };
                    Texture { step: 1.0, bias: 0.0, ..t.with_data(t.data.iter().map(|&v| decode(v)).collect()) }
                })
                .collect()
        }
        let texels = match self.texels {
            Texels::F32(t) => Texels::F64(wide(&t)),
            Texels::U8(t) => Texels::F64(wide(&t)),
            Texels::U16(t) => Texels::F64(wide(&t)),
            Texels::F16(t) => Texels::F64(wide(&t)),
            wide => wide,
        };
        Textures { shape: self.shape, texels }
    }

    /// Checks that these are the textures of `list`'s bricks.
    pub(crate) fn check(&self, list: &DrawList) -> Result<()> {
        fn all<S: Texel>(t: &[Texture<S>], list: &DrawList) -> bool {
            let border = usize::from(list.plan.bordered());
            t.len() == list.bricks.len()
                && t.iter().zip(&list.bricks).all(|(t, d)| t.is_of(&d.brick) && t.border == border)
        }
        let ok = match &self.texels {
            Texels::F32(t) => all(t, list),
            Texels::F64(t) => all(t, list),
            Texels::U8(t) => all(t, list),
            Texels::U16(t) => all(t, list),
            Texels::F16(t) => all(t, list),
        };
        if ok {
            Ok(())
        } else {
            Err(Error::InvalidArgument(
                "textures: they were uploaded for another DrawList; upload this DrawList's bricks".into(),
            ))
        }
    }
}

/// Uploads `list`'s brick textures from `grid` (bricks in parallel), with
/// a gradient border when the list takes gradients ([`bordered_position`]).
pub fn upload(grid: &Grid<'_>, list: &DrawList) -> Result<Textures> {
    upload_field(grid, list, list.plan.gradients())
}

/// [`upload`] of a field whose gradient the executor reads (`gradients`:
/// the [`Texture::lattice_differences`] are made) or not (the opacity field
/// of dependent components: bordered like the colour field, its gradient
/// never taken).
pub(crate) fn upload_field(grid: &Grid<'_>, list: &DrawList, gradients: bool) -> Result<Textures> {
    let shape = *grid.shape();
    check_bricks(list, &shape)?;
    Ok(Textures { shape, texels: grid.visit(Upload(list, gradients)) })
}

/// The DrawList, and whether the textures get their lattice differences.
struct Upload<'a>(&'a DrawList, bool);

impl GridVisitor for Upload<'_> {
    type Output = Texels;
    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Texels {
        let bricks = &self.0.bricks;
        let how = (usize::from(self.0.plan.bordered()), self.0.plan.blend.mode, self.1);
        let enc = self.0.texel;
        let step = match enc.format.levels() {
            0 => 1.0,
            levels => enc.scale / f64::from(levels),
        };
        let code = |v: f64| enc.encode(v);
        match enc.format {
            TexelFormat::Unorm8 => Texels::U8(
                bricks
                    .par_iter()
                    .map(|d| Texture::prepared(&g, &d.brick, how, |v| Some(code(v) as u8), (step, enc.bias)))
                    .map(|t| t.expect("every value has a code"))
                    .collect(),
            ),
            TexelFormat::Unorm16 => Texels::U16(
                bricks
                    .par_iter()
                    .map(|d| Texture::prepared(&g, &d.brick, how, |v| Some(code(v) as u16), (step, enc.bias)))
                    .map(|t| t.expect("every value has a code"))
                    .collect(),
            ),
            TexelFormat::Float16 => Texels::F16(
                bricks
                    .par_iter()
                    .map(|d| {
                        let half = |v| Some(half::f16::from_bits(code(v) as u16));
                        Texture::prepared(&g, &d.brick, how, half, (enc.scale, enc.bias))
                    })
                    .map(|t| t.expect("every value has a code"))
                    .collect(),
            ),
            TexelFormat::Auto | TexelFormat::Float32 => {
                let f32s: Option<Vec<Texture<f32>>> =
                    bricks.par_iter().map(|d| Texture::prepared(&g, &d.brick, how, f32::exact, (1.0, 0.0))).collect();
                match f32s {
                    Some(t) => Texels::F32(t),
                    None => Texels::F64(
                        bricks
                            .par_iter()
                            .map(|d| {
                                Texture::prepared(&g, &d.brick, how, f64::exact, (1.0, 0.0)).expect("f64 holds f64")
                            })
                            .collect(),
                    ),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::{Grid, Samples};
    use crate::octree::trilinear;
    use crate::render::sample::trilinear as grid_trilinear;

    fn brick(lo: [usize; 3], hi: [usize; 3], stride: usize) -> Brick {
        crate::plan::select::test_brick(0, lo, hi, stride)
    }

    const BRICKS: [([usize; 3], [usize; 3], usize); 4] = [
        ([0, 0, 0], [8, 8, 8], 4),
        ([8, 0, 8], [10, 8, 10], 4),
        ([4, 4, 4], [6, 6, 6], 1),
        ([2, 4, 2], [10, 10, 8], 2),
    ];

    /// The copied texture is T_p: equal, bit for bit, to the octree's
    /// definition at every grid point of the brick, clipped bricks included,
    /// and to the grid read at the texel positions (no copy) everywhere between.
    struct SameAsTp<S>(std::marker::PhantomData<S>);
    impl<S: Texel> GridVisitor for SameAsTp<S> {
        type Output = ();
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) {
            for (lo, hi, s) in BRICKS {
                let b = brick(lo, hi, s);
                let tex = Texture::<S>::copy(&g, &b, 0).unwrap();
                for z in lo[2]..=hi[2] {
                    for y in lo[1]..=hi[1] {
                        for x in lo[0]..=hi[0] {
                            let p = [x as f64, y as f64, z as f64];
                            assert_eq!(tex.value(p), trilinear::eval(&g, s, x, y, z), "{lo:?} s {s} at {p:?}");
                        }
                    }
                }
                // Between texels and outside the brick (clamped): the same formula on the grid.
                let pos = |a: usize, i: usize| (lo[a] + i * s).min(hi[a]);
                for q in 0..500 {
                    let r = |m: usize| ((q * m) % 997) as f64 / 997.0;
                    let p = [0, 1, 2].map(|a| lo[a] as f64 - 1.0 + r(31 + 7 * a) * (hi[a] - lo[a] + 2) as f64);
                    let u = [0, 1, 2].map(|a| (p[a] - lo[a] as f64) / s as f64);
                    let direct = grid_trilinear(b.texels, u, |i, j, k| g.at(pos(0, i), pos(1, j), pos(2, k)));
                    assert_eq!(tex.value(p).to_bits(), direct.to_bits(), "{lo:?} s {s} at {p:?}");
                }
            }
        }
    }

    #[test]
    fn brick_texture_is_t_p() {
        let data: Vec<f64> = (0..11 * 11 * 11).map(|i| ((i * 7919) % 101) as f64 / 100.0).collect();
        let g = Grid::scalar(Samples::F64(&data), [11, 11, 11]).unwrap();
        g.visit(SameAsTp::<f64>(std::marker::PhantomData));
        let data: Vec<f32> = data.iter().map(|&v| v as f32).collect();
        let g = Grid::scalar(Samples::F32(&data), [11, 11, 11]).unwrap();
        g.visit(SameAsTp::<f32>(std::marker::PhantomData));
    }

    /// The GPU upload of a blend mode's brick is the CPU texture of a list of that mode.
    #[test]
    fn blend_upload_is_the_compositor_texture() {
        let data: Vec<f32> = (0..11 * 11 * 11).map(|i| ((i * 7919) % 101) as f32).collect();
        let g = Grid::scalar(Samples::F32(&data), [11, 11, 11]).unwrap();
        for (lo, hi, s) in BRICKS {
            let b = brick(lo, hi, s);
            for mode in BlendMode::ALL {
                let mut out = vec![0.0f32; b.texels.iter().product()];
                brick_texels_for_blend_f32_into(&g, &b, mode, &mut out).unwrap();
                struct Copy<'b>(&'b Brick, BlendMode);
                impl GridVisitor for Copy<'_> {
                    type Output = Vec<f32>;
                    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Vec<f32> {
                        Texture::<f32>::copy_for(&g, self.0, 0, self.1).unwrap().data
                    }
                }
                assert_eq!(out, g.visit(Copy(&b, mode)), "{mode:?} {lo:?} s {s}");
            }
            let mut short = vec![0.0f32; 1];
            assert!(brick_texels_for_blend_f32_into(&g, &b, BlendMode::Mip, &mut short).is_err());
        }
    }

    /// f32 storage only when exact: an f32 grid uploads as f32, an f64 grid
    /// of values that are not f32s as f64.
    #[test]
    fn storage_is_exact() {
        use crate::geometry::camera::Camera;
        use crate::plan::{BrickDraw, DrawList, Plan, SurfacePass};
        let list = |b: Brick| DrawList {
            plan: Plan {
                volume: true,
                surface: SurfacePass::None,
                shading: false,
                gradient_opacity: false,
                transfer_2d: false,
                opacity_scale: 1.0,
                skipped_bricks: 0,
                blend: Default::default(),
                passes: Vec::new(),
                dependent: false,
                rgba: false,
                effects: Vec::new(),
                jitter: false,
                scattering: false,
                sample_distance: None,
                min_slice_spacing: None,
            },
            camera: Camera::around([0.0; 3], [4.0; 3], 0.0, 0.0, true).unwrap(),
            bricks: vec![BrickDraw {
                brick: b,
                world_lo: [0.0; 3],
                world_hi: [4.0; 3],
                slice_spacing: 1.0,
                slices: Vec::new(),
                batches: Vec::new(),
                points: Vec::new(),
            }],
            opaque_triangles: Vec::new(),
            reference_spacing: 1.0,
            lighting: None,
            gradient_opacity: None,
            transfer_2d: None,
            scattering: None,
            region: None,
            texel: Default::default(),
        };
        let l = list(brick([0; 3], [4; 3], 1));
        let f64s: Vec<f64> = (0..125).map(|i| i as f64 / 10.0).collect();
        let t = upload(&Grid::scalar(Samples::F64(&f64s), [5, 5, 5]).unwrap(), &l).unwrap();
        assert!(matches!(t.texels, Texels::F64(_)) && t.bytes() == 125 * 8);
        let f32s: Vec<f32> = (0..125).map(|i| i as f32 / 10.0).collect();
        let t = upload(&Grid::scalar(Samples::F32(&f32s), [5, 5, 5]).unwrap(), &l).unwrap();
        assert!(matches!(t.texels, Texels::F32(_)) && t.bytes() == 125 * 4);
        t.check(&l).unwrap();
        let e = t.check(&list(brick([0; 3], [4; 3], 2))).unwrap_err().to_string();
        assert!(e.contains("another DrawList"), "{e}");
    }
}
