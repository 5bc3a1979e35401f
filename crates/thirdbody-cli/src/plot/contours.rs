//! Contour lines of a field sampled on a rectilinear set of cell centres, by marching
//! squares (the `contour` crate, a port of d3-contour), mapped to plot coordinates.
//!
//! The `contour` crate places sample `i` at index coordinate `i + 1/2` and closes every
//! line around the window by treating the outside as below the threshold. Index
//! coordinates are mapped piecewise linearly: `i + 1/2` to the centre `c_i`, `0` and `n`
//! to the outer cell edges. Segments touching the window border come from that closing
//! and are dropped, so a line that leaves the window ends at the outermost cell centres.

use anyhow::{anyhow, Result};
use contour::ContourBuilder;

/// Positions of the cells along one axis: centres (increasing) and the two outer edges.
#[derive(Debug, Clone)]
pub(crate) struct Axis {
    pub centres: Vec<f64>,
    pub first_edge: f64,
    pub last_edge: f64,
}

impl Axis {
    /// Cells of equal width `cell` starting at `origin`.
    pub fn uniform(n: usize, origin: f64, cell: f64) -> Self {
        Axis {
            centres: (0..n).map(|i| origin + (i as f64 + 0.5) * cell).collect(),
            first_edge: origin,
            last_edge: origin + n as f64 * cell,
        }
    }

    /// Cells centred on increasing `centres` (at least two); edges halfway between
    /// neighbours and half a spacing beyond the first and last centre.
    pub fn from_centres(centres: &[f64]) -> Self {
        let n = centres.len();
        Axis {
            centres: centres.to_vec(),
            first_edge: centres[0] - 0.5 * (centres[1] - centres[0]),
            last_edge: centres[n - 1] + 0.5 * (centres[n - 1] - centres[n - 2]),
        }
    }

    /// The same axis mirrored (`v -> -v`, still increasing).
    pub fn negated(&self) -> Self {
        Axis {
            centres: self.centres.iter().rev().map(|c| -c).collect(),
            first_edge: -self.last_edge,
            last_edge: -self.first_edge,
        }
    }

    pub fn len(&self) -> usize {
        self.centres.len()
    }

    /// Edge between cell `i - 1` and cell `i` (`i` in `0..=n`).
    pub fn edge(&self, i: usize) -> f64 {
        let n = self.len();
        if i == 0 {
            self.first_edge
        } else if i == n {
            self.last_edge
        } else {
            0.5 * (self.centres[i - 1] + self.centres[i])
        }
    }

    /// Index of the cell containing `v`, if inside the window.
    pub fn cell_of(&self, v: f64) -> Option<usize> {
        if !(v >= self.first_edge && v < self.last_edge) {
            return None;
        }
        // Binary search for the number of interior edges (1..n) at or below v.
        let (mut lo, mut hi) = (1, self.len());
        while lo < hi {
            let mid = (lo + hi) / 2;
            if self.edge(mid) <= v {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        Some(lo - 1)
    }

    /// Maps a contour-crate index coordinate `c` (sample `i` at `i + 1/2`) to a position.
    pub fn position(&self, c: f64) -> f64 {
        let n = self.len();
        let t = c - 0.5;
        if t <= 0.0 {
            let f = (t + 0.5) / 0.5;
            return self.first_edge + f.max(0.0) * (self.centres[0] - self.first_edge);
        }
        if t >= (n - 1) as f64 {
            let f = (t - (n - 1) as f64) / 0.5;
            return self.centres[n - 1] + f.min(1.0) * (self.last_edge - self.centres[n - 1]);
        }
        let i = t.floor() as usize;
        let f = t - i as f64;
        self.centres[i] + f * (self.centres[i + 1] - self.centres[i])
    }
}

/// Polylines (in plot coordinates) where the row-major `values` (`values[row * nx + col]`,
/// rows along `rows`) cross each of `thresholds`. `smooth`: interpolate the crossing
/// linearly between samples (else it lies halfway, i.e. on the cell edges).
/// `min_span`: a piece whose extent is below this many sample spacings along both axes
/// (a speck around one or two samples, whose shape the grid does not resolve) is left
/// out; 0 keeps every piece.
pub(crate) fn contour_lines(
    values: &[f64],
    cols: &Axis,
    rows: &Axis,
    thresholds: &[f64],
    smooth: bool,
    min_span: f64,
) -> Result<Vec<Vec<(f64, f64)>>> {
    let (nx, ny) = (cols.len(), rows.len());
    let lines = ContourBuilder::new(nx, ny, smooth)
        .lines(values, thresholds)
        .map_err(|e| anyhow!("contour lines failed: {e:?}"))?;
    let on_border = |p: &Point| {
        let near = |a: f64, b: f64| (a - b).abs() < 1e-9;
        near(p.0, 0.0) || near(p.0, nx as f64) || near(p.1, 0.0) || near(p.1, ny as f64)
    };
    let border_segment = |a: &Point, b: &Point| on_border(a) || on_border(b);
    // Extent of a piece in index coordinates (sample spacings), along each axis.
    let speck = |piece: &[Point]| {
        let span = |c: fn(&Point) -> f64| {
            let (lo, hi) = piece
                .iter()
                .map(c)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                    (a.min(v), b.max(v))
                });
            hi - lo
        };
        span(|p| p.0) < min_span && span(|p| p.1) < min_span
    };
    let mut pieces: Vec<Vec<Point>> = Vec::new();
    for line in &lines {
        for string in line.geometry().0.iter() {
            let mut points: Vec<Point> = string.0.iter().map(|c| (c.x, c.y)).collect();
            // A closed ring is cut where it touches the border: start it at such a
            // segment so that each visible piece comes out as one polyline.
            let closed = points.len() > 2 && points.first() == points.last();
            if let Some(k) = points
                .windows(2)
                .position(|w| border_segment(&w[0], &w[1]))
                .filter(|_| closed)
            {
                let m = points.len() - 1;
                let rotated: Vec<Point> = (0..=m).map(|s| points[(k + s) % m]).collect();
                points = rotated;
            }
            let mut current: Vec<Point> = Vec::new();
            for pair in points.windows(2) {
                if border_segment(&pair[0], &pair[1]) {
                    if current.len() > 1 {
                        pieces.push(std::mem::take(&mut current));
                    }
                    current.clear();
                    continue;
                }
                if current.is_empty() {
                    current.push(pair[0]);
                }
                current.push(pair[1]);
            }
            if current.len() > 1 {
                pieces.push(current);
            }
        }
    }
    let map = |p: &Point| (cols.position(p.0), rows.position(p.1));
    Ok(pieces
        .iter()
        .filter(|piece| !speck(piece))
        .map(|piece| piece.iter().map(map).collect())
        .collect())
}

/// A point in the contour crate's index coordinates.
type Point = (f64, f64);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_lookup_and_position_agree_with_the_grid_convention() {
        let axis = Axis::uniform(4, -1.0, 0.5);
        assert_eq!(axis.cell_of(-1.0), Some(0));
        assert_eq!(axis.cell_of(-0.26), Some(1));
        assert_eq!(axis.cell_of(0.99), Some(3));
        assert_eq!(axis.cell_of(1.0), None);
        assert_eq!(axis.cell_of(-1.01), None);
        // Sample i sits at index coordinate i + 1/2: the cell centre x0 + (i + 1/2) h.
        assert!((axis.position(2.5) - 0.25).abs() < 1e-15);
        assert!((axis.position(0.0) + 1.0).abs() < 1e-15);
        assert!((axis.position(4.0) - 1.0).abs() < 1e-15);
        let uneven = Axis::from_centres(&[0.0, 1.0, 3.0]);
        assert_eq!((uneven.first_edge, uneven.last_edge), (-0.5, 4.0));
        assert_eq!(uneven.cell_of(1.9), Some(1));
        assert_eq!(uneven.cell_of(2.1), Some(2));
        assert!((uneven.position(2.0) - 2.0).abs() < 1e-15);
        let flipped = uneven.negated();
        assert_eq!(flipped.centres, vec![-3.0, -1.0, 0.0]);
        assert_eq!((flipped.first_edge, flipped.last_edge), (-4.0, 0.5));
    }

    #[test]
    fn circle_contour_has_the_right_radius() {
        // f = x^2 + y^2 on a fine grid; the smoothed contour at 0.25 is the circle r = 0.5
        // within a fraction of a cell (linear interpolation of a quadratic).
        let n = 64;
        let h = 2.0 / n as f64;
        let axis = Axis::uniform(n, -1.0, h);
        let values: Vec<f64> = (0..n * n)
            .map(|k| {
                let (x, y) = (axis.centres[k % n], axis.centres[k / n]);
                x * x + y * y
            })
            .collect();
        let lines = contour_lines(&values, &axis, &axis, &[0.25], true, 0.0).unwrap();
        assert_eq!(lines.len(), 1);
        for &(x, y) in &lines[0] {
            let r = (x * x + y * y).sqrt();
            assert!((r - 0.5).abs() < 0.02 * h + 1e-3, "r = {r}");
        }
    }

    #[test]
    fn border_segments_are_dropped() {
        // Field above the threshold everywhere except a strip at the left: the only line is
        // the vertical boundary of the strip, not the window frame.
        let n = 10;
        let axis = Axis::uniform(n, 0.0, 1.0);
        let values: Vec<f64> = (0..n * n)
            .map(|k| if k % n < 3 { 0.0 } else { 1.0 })
            .collect();
        let lines = contour_lines(&values, &axis, &axis, &[0.5], false, 0.0).unwrap();
        assert_eq!(lines.len(), 1);
        // Unsmoothed: the line lies on the edge between cells 2 and 3, x = 3, and runs
        // from the first to the last row centre.
        for &(x, _) in &lines[0] {
            assert!((x - 3.0).abs() < 1e-12, "x = {x}");
        }
        let (y_min, y_max) = lines[0]
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
        assert_eq!((y_min, y_max), (0.5, 9.5));
    }

    #[test]
    fn specks_are_dropped_and_larger_pieces_kept() {
        // A dip of one sample in the middle and a dip of 4 x 4 samples in a corner region:
        // with a span of 3 only the larger ring remains.
        let n = 16;
        let axis = Axis::uniform(n, 0.0, 1.0);
        let mut values = vec![1.0; n * n];
        values[8 * n + 8] = 0.0;
        for j in 2..6 {
            for i in 2..6 {
                values[j * n + i] = 0.0;
            }
        }
        let all = contour_lines(&values, &axis, &axis, &[0.5], true, 0.0).unwrap();
        assert_eq!(all.len(), 2);
        let kept = contour_lines(&values, &axis, &axis, &[0.5], true, 3.0).unwrap();
        assert_eq!(kept.len(), 1);
        assert!(kept[0].iter().all(|&(x, y)| x < 7.0 && y < 7.0), "{kept:?}");
    }
}
