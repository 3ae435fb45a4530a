//! The cut of the Volume Octree at an error tolerance: the nodes an
//! error-driven traversal stops at (paper 1, section 2.1: nodes with
//! `e_0 <= Eu` are selected).

use super::layout::NodeId;
use super::volume_octree::VolumeOctree;
use crate::base::error::{Error, Result};

impl VolumeOctree {
    /// The first nodes from the root, in depth-first z, y, x order, whose
    /// normalised nodal error E_0 is at most `tolerance`, or that are terminal.
    /// The returned boxes tile the grid exactly once.
    pub fn cut(&self, tolerance: f64) -> Result<Vec<NodeId>> {
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(Error::InvalidArgument(format!(
                "error tolerance {tolerance} must be a finite number >= 0 (a fraction of the data range, e.g. 0.01)"
            )));
        }
        let mut out = Vec::new();
        let mut stack = vec![self.root()];
        while let Some(id) = stack.pop() {
            let node = self.node(id);
            if node.is_terminal() || f64::from(node.error(0)) <= tolerance {
                out.push(id);
            } else {
                let mut kids = self.children(id);
                kids.reverse();
                stack.extend(kids);
            }
        }
        Ok(out)
    }
}
