//! How well the estimated error ranks frames by their measured error:
//! Spearman's rank correlation,
//!
//! ```text
//! rho = cov(rank(x), rank(y)) / (sd(rank(x)) sd(rank(y)))
//! ```
//!
//! ranks from 1, ties given their mean rank (so it is Pearson's correlation
//! of the ranks). Pairs with a value that is not a number are left out;
//! `None` below 2 pairs or when either side's ranks are all equal.

/// Spearman's rank correlation of the pairs `(x, y)` (see the module documentation).
pub fn rank_correlation(pairs: &[(f64, f64)]) -> Option<f64> {
    let kept: Vec<(f64, f64)> = pairs.iter().copied().filter(|(x, y)| !x.is_nan() && !y.is_nan()).collect();
    if kept.len() < 2 {
        return None;
    }
    let rx = ranks(&kept.iter().map(|p| p.0).collect::<Vec<_>>());
    let ry = ranks(&kept.iter().map(|p| p.1).collect::<Vec<_>>());
    let n = kept.len() as f64;
    let (mx, my) = (rx.iter().sum::<f64>() / n, ry.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in rx.iter().zip(&ry) {
        sxy += (a - mx) * (b - my);
        sxx += (a - mx) * (a - mx);
        syy += (b - my) * (b - my);
    }
    (sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt())
}

/// Ranks from 1, ties at their mean rank.
fn ranks(v: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
    let mut r = vec![0.0; v.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && v[order[j + 1]] == v[order[i]] {
            j += 1;
        }
        let mean = (i + j) as f64 / 2.0 + 1.0;
        for &k in &order[i..=j] {
            r[k] = mean;
        }
        i = j + 1;
    }
    r
}
