//! What a frame draws from: a grid in memory, or an OME-Zarr store whose
//! bricks are read as the selection asks (the volume never in memory).

use hybrid_octree::grid::{Grid, GridShape, ScalarType};
use hybrid_octree::plan::DrawList;
use hybrid_octree::render::scattering::{shadow_for, ShadowVolume};
use hybrid_octree::render::texture::read::upload_read;
use hybrid_octree::render::texture::{upload, Textures};
use hybrid_octree::select::Brick;
use hybrid_octree::store::Store;
use hybrid_octree::volume::Volume;
use hybrid_octree::{Error, Result};

/// The volume a scene is drawn from.
#[derive(Clone, Copy)]
pub enum Field<'a> {
    /// In memory.
    Grid(&'a Grid<'a>),
    /// On disk: bricks read per frame from the level of their stride.
    Store(&'a Store),
}

impl Field<'_> {
    /// Samples per axis, spacing, origin.
    pub fn shape(&self) -> &GridShape {
        match self {
            Field::Grid(g) => g.shape(),
            Field::Store(s) => &s.shape,
        }
    }

    /// The samples' type.
    pub fn scalar_type(&self) -> ScalarType {
        match self {
            Field::Grid(g) => g.samples().scalar_type(),
            Field::Store(s) => s.scalar_type,
        }
    }

    /// NaN samples (no data).
    pub fn nan_count(&self) -> usize {
        match self {
            Field::Grid(g) => g.nan_count(),
            Field::Store(s) => s.metadata().map_or(0, |m| m.nan_count),
        }
    }

    /// The grid, for what needs every sample (`what`); a store refuses with
    /// what to do.
    pub fn grid(&self, what: &str) -> Result<&Grid<'_>> {
        match self {
            Field::Grid(g) => Ok(g),
            Field::Store(s) => Err(Error::InvalidArgument(format!(
                "{what} needs every sample in memory, and '{}' is drawn from disk: leave it out, or read a \
                 volume that fits in memory (--in-memory)",
                s.label()
            ))),
        }
    }

    /// The DrawList's brick textures.
    pub fn upload(&self, list: &DrawList) -> Result<Textures> {
        match self {
            Field::Grid(g) => upload(g, list),
            Field::Store(s) => upload_read(&s.shape, list, |b, border| read_brick(s, b, border)),
        }
    }

    /// The shadow volume of a list that scatters light.
    pub fn shadow(&self, list: &DrawList) -> Result<Option<ShadowVolume>> {
        match self {
            Field::Grid(g) => shadow_for(g, list),
            Field::Store(_) if list.plan.scattering => self.grid("volumetric scattering").map(|_| None),
            Field::Store(_) => Ok(None),
        }
    }
}

/// Brick `b`'s texels with `border`, from the store's level of its stride.
fn read_brick(store: &Store, b: &Brick, border: usize) -> Result<Volume> {
    store.read_texels(b.stride, b.lo, b.texels, border)
}
