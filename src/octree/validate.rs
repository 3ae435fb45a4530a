//! The well-formedness check of a Volume Octree. Every test that builds an
//! octree calls it; debug builds assert it after every build.

use super::volume_octree::VolumeOctree;

impl VolumeOctree {
    /// Checks the invariants of a built octree and names the first one broken:
    ///
    /// - array lengths match the layout;
    /// - every node's `min <= max`, both finite, or the empty range
    ///   `(+inf, -inf)` of a box of NaN only; a parent's min/max are the
    ///   min/max of its children's;
    /// - every E_p is finite, in `[0, 1]`, and non-increasing in p;
    /// - `E_p(parent) = max over children of E_(p-1)(child)` for p >= 1 (the
    ///   stride of p in the parent is the stride of p-1 in a child);
    /// - children's boxes tile the parent's box (sum of cell counts);
    /// - the reachable terminal nodes tile the grid exactly once.
    pub fn validate(&self) -> Result<(), String> {
        let l = &self.layout;
        let slots = l.node_slots();
        if self.min.len() != slots || self.max.len() != slots {
            return Err(format!(
                "min/max arrays have {}/{} entries, layout needs {slots}",
                self.min.len(),
                self.max.len()
            ));
        }
        let expected: usize = (0..l.levels())
            .map(|k| {
                let d = l.level_dims(k);
                d[0] * d[1] * d[2] * l.error_count(k)
            })
            .sum();
        if self.errors.len() != expected {
            return Err(format!("error array has {} entries, layout needs {expected}", self.errors.len()));
        }
        for level in 0..l.levels() {
            let d = l.level_dims(level);
            for z in 0..d[2] {
                for y in 0..d[1] {
                    for x in 0..d[0] {
                        let node = self.node(l.id(level, [x, y, z]));
                        let at = format!("node {:?} (level {level}, coords {:?})", node.id, node.coords);
                        let empty = node.min == f64::INFINITY && node.max == f64::NEG_INFINITY;
                        if !(empty || (node.min.is_finite() && node.max.is_finite() && node.min <= node.max)) {
                            return Err(format!("{at}: bad range [{}, {}]", node.min, node.max));
                        }
                        for (p, w) in node.errors.windows(2).enumerate() {
                            if w[1] > w[0] {
                                return Err(format!("{at}: E_{} = {} > E_{p} = {}", p + 1, w[1], w[0]));
                            }
                        }
                        if let Some(e) = node.errors.iter().find(|e| !(e.is_finite() && (0.0..=1.0).contains(*e))) {
                            return Err(format!("{at}: nodal error {e} outside [0, 1]"));
                        }
                        if level == l.leaf_level() {
                            continue;
                        }
                        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                        let mut child_max = vec![0.0f32; node.errors.len().saturating_sub(1)];
                        let mut cells = 0usize;
                        for (cl, cc) in l.children(level, node.coords) {
                            let c = self.node(l.id(cl, cc));
                            lo = lo.min(c.min);
                            hi = hi.max(c.max);
                            for (p, m) in child_max.iter_mut().enumerate() {
                                *m = m.max(c.error(p));
                            }
                            cells += (0..3).map(|a| c.hi[a] - c.lo[a]).product::<usize>();
                        }
                        if lo != node.min || hi != node.max {
                            return Err(format!(
                                "{at}: range [{}, {}] is not its children's [{lo}, {hi}]",
                                node.min, node.max
                            ));
                        }
                        for (p, m) in child_max.iter().enumerate() {
                            if node.error(p + 1) != *m {
                                return Err(format!(
                                    "{at}: E_{} = {} but the children's E_{p} reach {m}",
                                    p + 1,
                                    node.error(p + 1)
                                ));
                            }
                        }
                        let own: usize = (0..3).map(|a| node.hi[a] - node.lo[a]).product();
                        if cells != own {
                            return Err(format!("{at}: children cover {cells} cells of its {own}"));
                        }
                    }
                }
            }
        }
        let mut covered = 0usize;
        self.for_each_node(|n| {
            if n.is_terminal() {
                covered += (0..3).map(|a| n.hi[a] - n.lo[a]).product::<usize>();
            }
        });
        let total: usize = (0..3).map(|a| l.dims[a] - 1).product();
        if covered != total {
            return Err(format!("terminal nodes cover {covered} cells of the grid's {total}"));
        }
        Ok(())
    }
}
