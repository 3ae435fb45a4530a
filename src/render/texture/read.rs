//! Brick textures from samples read per brick, for volumes that are not in
//! memory (an OME-Zarr store): each brick's texels arrive as a small volume
//! of exactly its texel lattice, border included, and become its texture
//! as if the brick were a stride-1 brick of that volume. The textures are
//! the ones [`super::upload`] makes from the whole grid, bit for bit, when
//! the read samples are the grid's at the texel positions.

use super::{Texel, Texels, Texture, Textures};
use crate::base::error::{Error, Result};
use crate::data::grid::{GridShape, GridVisitor, Sample, TypedGrid};
use crate::data::volume::Volume;
use crate::plan::select::Brick;
use crate::plan::texel_format::TexelFormat;
use crate::plan::{BlendMode, BrickDraw, DrawList};
use rayon::prelude::*;

/// Uploads `list`'s brick textures from `read(brick, border)`: the brick's
/// `(n + 2 border)` texels per axis (texel `i` at `lo + (i - border) stride`,
/// clamped to the grid, x fastest), bricks in parallel.
///
/// # Errors
///
/// What `read` returns; [`Error::InvalidArgument`] for a read volume of the
/// wrong size, or for maximum and minimum intensity lists with coarse
/// bricks, whose peak-keeping texels need the full-resolution samples.
pub fn upload_read(
    shape: &GridShape,
    list: &DrawList,
    read: impl Fn(&Brick, usize) -> Result<Volume> + Sync,
) -> Result<Textures> {
    super::check_bricks(list, shape)?;
    if list.plan.blend.mode.is_extremum() && list.bricks.iter().any(|d| d.brick.stride > 1) {
        return Err(Error::InvalidArgument(
            "maximum and minimum intensity need each coarse texel's peak over its stride, which a store's \
             subsampled levels do not hold: read the volume into memory (the CLI's --in-memory), or raise the budget \
             so that every brick is at full resolution"
                .into(),
        ));
    }
    let border = usize::from(list.plan.bordered());
    let how = (border, list.plan.blend.mode, list.plan.gradients());
    let enc = list.texel;
    let step = match enc.format.levels() {
        0 => 1.0,
        levels => enc.scale / f64::from(levels),
    };
    let code = |v: f64| enc.encode(v);
    let one = |d: &BrickDraw| -> Result<Volume> {
        let v = read(&d.brick, border)?;
        let n = d.brick.texels.map(|n| n + 2 * border);
        if v.shape.dims != n || v.components != 1 {
            return Err(Error::InvalidArgument(format!(
                "brick (node {}) read {:?} samples, its texture has {n:?}",
                d.brick.node.0, v.shape.dims
            )));
        }
        Ok(v)
    };
    let fail = |e: Option<Error>| e.unwrap_or_else(|| Error::InvalidArgument("a texel value has no code".into()));
    let texels = match enc.format {
        TexelFormat::Unorm8 => {
            Texels::U8(make(list, &one, how, |v| Some(code(v) as u8), (step, enc.bias)).map_err(fail)?)
        }
        TexelFormat::Unorm16 => {
            Texels::U16(make(list, &one, how, |v| Some(code(v) as u16), (step, enc.bias)).map_err(fail)?)
        }
        TexelFormat::Float16 => Texels::F16(
            make(list, &one, how, |v| Some(half::f16::from_bits(code(v) as u16)), (enc.scale, enc.bias))
                .map_err(fail)?,
        ),
        TexelFormat::Auto | TexelFormat::Float32 => match make(list, &one, how, f32::exact, (1.0, 0.0)) {
            Ok(t) => Texels::F32(t),
            Err(None) => Texels::F64(make(list, &one, how, f64::exact, (1.0, 0.0)).map_err(fail)?),
            Err(Some(e)) => return Err(e),
        },
    };
    Ok(Textures { shape: *shape, texels })
}

/// Every brick's texture of `S` (`Err(None)`: a value `f` refuses).
fn make<S: Texel, F: Fn(f64) -> Option<S> + Sync + Send>(
    list: &DrawList,
    read: &(dyn Fn(&BrickDraw) -> Result<Volume> + Sync),
    how: (usize, BlendMode, bool),
    f: F,
    decode: (f64, f64),
) -> std::result::Result<Vec<Texture<S>>, Option<Error>> {
    list.bricks
        .par_iter()
        .map(|d| {
            let v = read(d).map_err(Some)?;
            let grid = v.grid(None).map_err(Some)?;
            let b = how.0;
            let n = d.brick.texels;
            let local = Brick { lo: [b; 3], hi: n.map(|n| b + n - 1), stride: 1, ..d.brick };
            let t = grid.visit(OneBrick { brick: &local, how, f: &f, decode }).ok_or(None)?;
            Ok(Texture { lo: d.brick.lo, hi: d.brick.hi, stride: d.brick.stride, ..t })
        })
        .collect()
}

/// One brick's texture from its own small grid.
struct OneBrick<'a, F> {
    brick: &'a Brick,
    how: (usize, BlendMode, bool),
    f: &'a F,
    decode: (f64, f64),
}

impl<S: Texel, F: Fn(f64) -> Option<S>> GridVisitor for OneBrick<'_, F> {
    type Output = Option<Texture<S>>;
    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Option<Texture<S>> {
        Texture::prepared(&g, self.brick, self.how, self.f, self.decode)
    }
}
