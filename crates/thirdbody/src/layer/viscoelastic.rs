//! Any layer rheology of the creep form ([`super::rheology::CreepForm`]: glassy
//! spring, Kelvin–Voigt branches, viscous flow, every part scaled by the law's
//! shape `phi(p) = C[p] / C[0]`) integrated along the material path in the steady
//! sliding frame, where `d/dt = -V d/dx` (docs/architecture.md, conventions).
//! Material enters the window at its largest x and moves in -x; the pressure is
//! constant over a cell (side h), so each part is integrated exactly over a cell:
//!
//! * glassy: `w_g,i = (C_g / C[0]) F(p_i)`, with `F(p) = G(p) = int_0^p C[q] dq`
//!   (`exact`) or `C[p] p` (`secant`);
//! * flow (paper eq. 2's dashpot): `dw_v/dt = (C_v / C[0]) C[p] p / T`, so at the
//!   centre of cell i
//!   `w_v,i = (C_v / C[0]) (h / (V T)) (sum_{j upstream} C[p_j] p_j + C[p_i] p_i / 2)`;
//! * Kelvin–Voigt branch k: `tau_k dw_k/dt + w_k = (C_k / C[0]) F(p)`, a first-order
//!   linear ODE along the row, `L_k dw_k/ds = (C_k / C[0]) F - w_k` with the creep
//!   length `L_k = V tau_k` and s along the path. Its forcing over cell i is
//!   reconstructed linearly, `F_i + sigma_i (x - x_i)` with the centred slope
//!   `sigma_i = (F_{i+1} - F_{i-1}) / (2h)` (`F = 0` beyond the window), and the
//!   ODE is integrated exactly: with `x = h / L_k`, `a = e^(-x)`, `b = e^(-x/2)`,
//!   the value entering the next cell is
//!   `e_out = a e_in + (1 - a) F_i + g_full(x) h sigma_i` and the centre value
//!   `w_k,i = b e_in + (1 - b) F_i + g_half(x) h sigma_i` (times `C_k / C[0]`;
//!   `e = 0` where material enters), `g_half = (1 - b)/x - b/2`,
//!   `g_full = (1 - a)/x - (1 + a)/2`. When the creep length is shorter than a
//!   cell each branch relaxes within the cell, and the slope term is what keeps
//!   the lag `w ~ F + L_k dF/dx` that makes the friction (`g_half -> 1/x`): with a
//!   cell-wise constant forcing it was lost (the friction of a Kelvin–Voigt layer
//!   at `L = h / 100` came out zero). Where the cell is much shorter than the
//!   creep length the constant forcing is already of second order and the slope,
//!   which couples a cell to its downstream neighbour, would undamp the odd–even
//!   mode below: it is kept in the share `1 - exp(-(10 h / L_k)^2)`. In the last
//!   loaded cell before a trailing edge the forcing falls to zero inside the cell
//!   along the loaded side's line, and the centred slope, reading the unloaded
//!   neighbour's 0, about halved that cell's lag: the friction of a creep length
//!   far below the cell, made by the lag alone, came out first-order low (0.6 % on
//!   a rigid base with a contact half-length of 53 cells, 2.3 % on an elastic
//!   body). The slope therefore takes `min(0, F_{i-1} + 2 F_i - F_{i+1})` more of
//!   the downstream forcing: with the neighbour unloaded and the line through the
//!   other two centres negative at its centre, the slope is the one-sided
//!   `(F_{i+1} - F_i) / h`; where the forcing is linear and positive, or rises by
//!   less than the sum of the two lower values, nothing changes; and the forcing
//!   stays continuous as cells load and unload (a switch on the neighbour's load
//!   made the contact problem discontinuous, and an active-set solve cycled). Then
//!   0.02-0.07 % and 1.3 % (docs/validation.md).
//!
//! The exact centre value has, for a branch without a glassy spring in series, an
//! undamped odd–even mode: imposing `w_i` at the centre fixes each cell's pressure
//! from half a cell of response, and the error factor from one cell to the next is
//! `-b`, so the pressure jump at a Kelvin–Voigt layer's leading edge rings across
//! the contact (up to twice the jump) however fine the grid. The centre value used
//! is therefore the exact one plus the upwind correction
//! `kappa s (b - a) e^(-2x) (F_i - F_{i+1})` (`F` of the upstream cell, 0 beyond the
//! window), with `kappa = 0.1` and `s` the branches' share of a cell's own response
//! at zero pressure, `sum (1 - b_k) C_k / (C_g + sum (1 - b_k) C_k)` (near 1 for a
//! Kelvin–Voigt layer, near 0 when a glassy spring dominates, which needs no
//! correction). The error factor of the mode then has modulus about 0.57 per cell
//! instead of 1 (the characteristic roots of the two-term recursion, determinant
//! `a gamma / theta`), while for a smooth pressure the correction is
//! `kappa s (b - a) h dF/dx = O(h^2 / (V tau))`, of the scheme's own second order.
//! Larger kappa damps faster but raises that error (0.2 doubles it), and a
//! second-difference correction is unstable beyond kappa = 0.3. The factor
//! `e^(-2x)` fades the correction where cells are longer than the creep length:
//! there it would bias the lag by `kappa (b - a)` of a cell's slope (5 % of the
//! friction at `L = h / 3`) and there is no mode to damp.
//!
//! The mode is excited where the leading edge's jump falls inside a cell: with the
//! edge taken at the cell's face the first cells overshot by up to 1.8 times the
//! jump. The edge's position comes from the solution, so the solvers solve again
//! with it ([`LayerResponse::relocated`], until it stays put: two or three
//! solves): in a row's first loaded cell i, whose upstream neighbour is open, the
//! free gap (the gap less the layer's response to the cell's own load) closes
//! linearly between the two centres, so the edge lies
//! `theta = t_i / (t_i + g_{i+1})` cells upstream of the centre (`t_i` what the
//! cell's load takes up, `g_{i+1}` the neighbour's gap). Each branch relaxes freely
//! from the upstream centre to the edge and is forced from there by
//! `F_i + d (s - theta)`, `d = F_{i-1} - F_i` (one-sided: the forcing jumps at the
//! edge), exactly: the centre value is
//! `e^(-x) w_{i+1} + (1 - e^(-y)) F_i - d theta entry_lag(y)`, `y = theta x`, with
//! neither upwind term nor centred slope there, and the upstream neighbour's slope
//! stops at the edge. The cell's mean pressure, which the body and the load see, is
//! the integral of the pressure from the edge ([`super::ContactEdge`]). Trailing
//! edges, where the pressure falls continuously to zero, are placed where the
//! pressure's line through the last two centres reaches zero while a branch lags
//! (it leaves the free gap a kink there), and where the free gap closes, as leading
//! edges are, once the branches relax within a few cells: the two ends of a contact
//! then have the same errors, which cancel in the friction of a nearly relaxed
//! layer (the small difference between them). A flow's trailing edges are placed
//! by the free gap too (by the pressure's line, the placement is neutral: the
//! cell's centre value follows the edge so that its mean stays, and the edge
//! stopped wherever its iteration began, a result that depended on the units to
//! 2e-7). The flow places edges only where a cell of it exceeds the springs'
//! response (`h / (V T) > C_g / C_v` without branches): below, the pressure rises
//! behind the leading edge over a cell or more, and the edges changed the friction
//! by less than 2e-4 at two to three times the cost. No edges are placed where the
//! flow places none and every branch is frozen (infinite speed) or relaxed within
//! a cell to the last double: the layer is then a spring bed, and its contact the
//! spring bed's.
//!
//! The flow's centre value has the same kind of mode. With `r = h / (V T)` and the
//! glassy spring in series, imposing `w_i` fixes `(1 + r/2) p_i + (r/2 - 1)
//! p_{i+1} = ...` (the trapezoidal rule's recursion): the error factor per cell is
//! `-(r - 2) / (r + 2)`, near -1 where the creep length is far below the cell (the
//! slow limit of the paper's Maxwell layer, and always -1 for a flow without a
//! spring). Undamped, the leading edge's jump rang across the contact: at `V T =
//! h / 40` the peak pressure came out up to 75 % high and the power dissipated,
//! which weighs `p^2`, 10-20 % above the slope's friction (the friction itself, a
//! linear functional, was right). The flow's centre value is therefore
//! `(h / V T) (sum_{j upstream} q_j + q_i / 2 + kappa (q_i - q_{i+1}))`, `q = C[p]
//! p`: for a smooth pressure the correction is `O(h^2 / (V T))` against the flow's
//! `O(h / (V T))` per cell, of the scheme's own second order, and in the slow limit
//! with `kappa = 1/16` the recursion's two roots are both -1/3 (1/16 makes them
//! equal; larger or smaller shares leave one of them larger). Where the mode does
//! not alternate (`r < 2`, with `r` the flow per cell over the springs' own
//! response) nothing needs damping and the correction would only bias the lag (it
//! doubled the friction's error on a rigid base at `V T = 10 h`), so `kappa =
//! (r - 2) / (r + 2) / 16`: 0 up to r = 2, 1/16 in the slow limit and for a flow
//! without a spring, the roots within 1/3 throughout. Its leading edges are
//! located as the branches' are (above): in an entry cell the creep rate is
//! integrated from the edge, linear through the downstream neighbour's
//! (`theta q_i - theta^2 (q_{i-1} - q_i) / 2` at the centre, without the
//! correction), and the cell passes downstream the rate integrated over its loaded
//! part, with the weights of its mean pressure ([`ContactEdge::mean_weights`]).
//! Behind a leading edge the springs take the pressure up from the flow's: for
//! the paper's Maxwell layer `C_g p + (flow per cell) int_0^s p = I(s)` with the
//! interference `I ~ I' s` gives `p = A (1 - e^(-s / l))`, `l = C_g / (flow per
//! cell)` cells, below a cell wherever the flow places edges; each retarded branch
//! adds an exponential (`layer_rise`: the roots of the layer's transfer function,
//! `sum a_m l_m` the relaxed springs over the flow). The entry cell's pressure,
//! forcing and creep rate are therefore their line through the two centres times
//! `rho(s) = 1 - sum_m a_m e^(-s / l_m)` ([`ContactEdge::rise`]): the centre value
//! is the line's, the glassy spring sees the pressure at the centre (`rho(theta)`
//! of it), the branches' centre and exit values are their equation's solution under
//! that forcing (`BranchStep::entry_gains`, `exit_deficit`), and the flow to the
//! centre, the flow passed downstream, the cell's mean pressure and its dissipated
//! power are the profile's integrals. With the pressure jumping at the edge
//! instead, the line carried a load `A sum a_m l_m` the rise does not, which the
//! flow passed downstream, and the next centre made it up by overshooting: 12 %
//! of the peak at `V T = h / 10` on a rigid base, 1 % or less with the rise (the
//! Maxwell and Burgers layers; 1.4 % at `V T = 0.3 h` where a Burgers layer's
//! slower exponential spans most of a cell). Where the edge lies within `l / 10`
//! of the centre the rise is shortened (`rise_behind`).
//! Without the correction and the edges this is the sum of paper eq. 8 read with
//! the loaded cell's compliance (`secant`) or its exact integral (`exact`); the
//! other reading of eq. 8, with the receiving cell's compliance multiplying all
//! upstream creep, folds at low `V T / h` and is not offered.
//!
//! Applying the layer is one sweep per row from the leading edge with one state per
//! branch: O(n (1 + branches)). Rows (fixed y) do not interact. The
//! Jacobian is lower triangular in the material order but for one entry per cell:
//! the centred slope's dependence on the downstream neighbour, which the Newton
//! preconditioner leaves out.
//!
//! The power dissipated ([`ViscoelasticRows::dissipated_force`]) is the power of the
//! pressure on the parts that do not store energy: `p dw_v/dt` for the flow and
//! `(p - F_k^{-1}(w_k)) dw_k/dt` for branch k. Over a cell the flow dissipates
//! `p_i (w_v,out - w_v,in)`, in an entry cell `int p dw_v` over its loaded part with
//! the pressure and the creep rate linear as above. Downstream of the window a
//! branch relaxes at zero pressure and dissipates the energy it still holds, so
//! summed along a whole row
//! the stored energies `Phi_k(w) = int_0^w F_k^{-1}` cancel and the branch
//! dissipates exactly `int p dw_k` along the row. That integral is taken exactly
//! for the pressure and forcing continuous and linear between cell centres (two
//! half-cell ramps per cell, `BranchStep::half_cell_work`): a profile that jumps
//! at cell faces (the cell-wise reconstruction above) would dissipate each jump
//! `dF^2 / 2C` anew when the creep length is shorter than a cell, an artefact that
//! outgrew the friction itself in the slow limit. This estimate is independent of
//! the slope-based friction `sum p df/dx h^2 / Q`; the two agree to the grid's
//! resolution of the contact's edges ([`crate::report::ENERGY_IMBALANCE_PER_CELL`]).

use rayon::prelude::*;

use super::law::SIGMOID_MONOTONE_DELTA;
use super::rheology::{CreepForm, Flow};
use super::{
    exponential_moments, ComplianceLaw, ContactEdge, Integration, Layer, LayerLinearisation,
    LayerResponse, Rise, RISE_TERMS,
};
use crate::body::quadrature::GaussLegendre;
use crate::convolution::Parallelism;
use crate::passes::{Passes, CHUNK};

/// `sum_k u_k v_k` with four partial sums, so that the additions of a long branch
/// list overlap instead of waiting on each other.
fn dot(u: &[f64], v: &[f64]) -> f64 {
    let mut lanes = [0.0; 4];
    let (uc, vc) = (u.chunks_exact(4), v.chunks_exact(4));
    let tail: f64 = uc
        .remainder()
        .iter()
        .zip(vc.remainder())
        .map(|(a, b)| a * b)
        .sum();
    for (a, b) in uc.zip(vc) {
        for j in 0..4 {
            lanes[j] += a[j] * b[j];
        }
    }
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) + tail
}

/// Fraction of the full upwind correction applied (module docs).
const UPWIND: f64 = 0.1;

/// Share of the flow's upwind correction `FLOW_UPWIND (h / V T) (q_i - q_upstream)`
/// in the slow limit (module docs): 1/16 puts both roots of that limit's recursion
/// at -1/3, the strongest damping of the odd-even mode this correction gives.
const FLOW_UPWIND: f64 = 1.0 / 16.0;

/// The flow's upwind share at `r` cells of flow per cell of the springs' response:
/// [`FLOW_UPWIND`] times the mode's own error factor `(r - 2) / (r + 2)` where it
/// alternates (r > 2), 0 where it does not (the scheme is then left as it was); the
/// recursion's roots stay within 1/3 at every r (module docs).
fn flow_upwind_share(r: f64) -> f64 {
    if r.is_infinite() {
        FLOW_UPWIND
    } else if r > 2.0 {
        FLOW_UPWIND * (r - 2.0) / (r + 2.0)
    } else {
        0.0
    }
}

/// Share of a cell's own response (half a cell of flow against the springs' and
/// that) below which the flow does not place the contacts' edges: 1/3, where a
/// whole cell of flow equals the springs' response (`h / (V T) = 1` for the
/// paper's Maxwell layer). Below it the pressure's rise behind a leading edge,
/// over `(C_g / C_v) V T`, spans a cell or more and the centre values follow it
/// (and the mode the upwind correction damps does not alternate: its factor
/// `-(r - 2) / (r + 2)` is positive below r = 2); there the located edges changed
/// the friction by less than 2e-4 and cost two to three times the solve (the
/// paper's Fig. 3 at 256^2: 198 ms without them, 483 ms with).
const FLOW_EDGE_SHARE: f64 = 1.0 / 3.0;

/// Share of a cell's own response below which the branches that move within it do
/// not place the contacts' edges: nearly frozen branches (a cell a millionth of
/// their creep length) in series with a glassy spring carry nothing across a cell,
/// and their edges only put the spring bed's symmetric contact out of balance
/// (a Zener layer at V = 1e7: mu -7e-8 instead of 0, the pressure asymmetric by
/// 4e-4 of its peak). Without a glassy spring the branches are the whole response
/// and always place the edges (the pressure jumps there).
const MOVING_BRANCH_SHARE: f64 = 1e-3;

/// Smallest distance from a contact's edge to its entry cell's centre, in cells.
const MIN_ENTRY: f64 = 1e-6;

/// Change of an entry fraction, relative to the larger of its old and new values
/// and [`ENTRY_FLOOR`], below which a located edge has not moved: the entry cell's
/// pressure errs by as much.
const ENTRY_TOLERANCE: f64 = 1e-4;

/// Smallest entry fraction [`ENTRY_TOLERANCE`] is relative to, so that a leading
/// edge holds still to 1e-5 cell at least. Without it an edge that nears its
/// cell's centre (theta falling by half a solve towards 0) never counted as
/// settled, and the relocations ran out (a Kelvin–Voigt layer on 512²; the entry
/// cell's share of the load is then about 1e-5 of a full cell's).
const ENTRY_FLOOR: f64 = 0.1;

/// Share of its move an edge makes from one solve to the next (module docs): the
/// approach's response to the edges' loads turns the plain update into an
/// alternating one with a factor of about -1/2 per solve, which 2/3 removes.
const RELOCATION_STEP: f64 = 2.0 / 3.0;

/// Change of a trailing edge's position, in cells, below which it has not moved
/// (it sets only how much load a cell carries, where the pressure is small).
const EXIT_TOLERANCE: f64 = 1e-2;

/// Shift, in cells, within which an edge that passed a cell's centre has not
/// moved: where an edge lies at a centre, the solves alternate between that cell
/// barely loaded and its neighbour entered a full cell from the edge, the same
/// contact to within the shift. (0.05 until the last loaded cell before a trailing
/// edge took the one-sided slope, which widened the alternation of such an edge to
/// 0.055 cells: a Zener layer at V tau / h = 0.1 then ran all its relocations.)
const CENTRE_CROSSING: f64 = 0.1;

/// Where, in cells upstream of a centre whose free gap is `here <= 0`, the free gap
/// reaches zero on its way to `next > 0` one cell upstream: on the parabola through
/// `further`, the gap two cells upstream, when given (exact for a paraboloid on a
/// rigid base; the straight line misses by about `h / 8b` of a cell, b the
/// contact's half-length, which a Kelvin–Voigt entry cell's pressure takes in full
/// relative to theta), else on the straight line.
fn gap_closure(here: f64, next: f64, further: Option<f64>) -> f64 {
    let linear = -here / (next - here);
    let Some(further) = further else {
        return linear;
    };
    // g(s) = here + a s + c s (s - 1) through s = 0, 1, 2.
    let a = next - here;
    let c = 0.5 * (further - 2.0 * next + here);
    let b = a - c;
    let discriminant = b * b - 4.0 * c * here;
    if discriminant < 0.0 {
        return linear;
    }
    // The root of c s^2 + b s + here = 0 near the linear one, in the form without
    // cancellation (here < 0, b > 0 where the gap opens upstream).
    let root = -2.0 * here / (b + discriminant.sqrt());
    if (0.0..=1.0).contains(&root) {
        root
    } else {
        linear
    }
}

/// What the branches' reconstruction adds to the downstream neighbour's forcing in
/// the slope of a cell (forcings `downstream`, `here`, `upstream` at the three
/// centres; module docs): `min(0, downstream + 2 here - upstream)`. Where the
/// downstream neighbour is unloaded and the line through the other two centres is
/// negative at its centre (the forcing falls to zero within this cell, at a
/// trailing edge), the centred slope becomes the one-sided `(upstream - here) / h`;
/// wherever the forcing is linear and positive, or rises by less than the sum of
/// the two lower values, it is 0. Continuous in the forcings, so the contact
/// problem stays continuous as cells load and unload.
fn trailing_correction(downstream: f64, here: f64, upstream: f64) -> f64 {
    (downstream + 2.0 * here - upstream).min(0.0)
}

/// The downstream forcing in the slope of cell `i` of a row (not an entry cell),
/// and whether [`trailing_correction`] is in it: the row's first cell has none
/// beyond the window; upstream of an entry cell the forcing is zero up to the edge,
/// so the slope does not reach across it; elsewhere the neighbour's forcing plus
/// the trailing correction. The sweep and the Jacobian both decide here.
fn slope_downstream(
    i: usize,
    entry_below: f64,
    below: f64,
    here: f64,
    upstream: f64,
) -> (f64, bool) {
    if i == 0 || entry_below > 0.0 {
        (0.0, false)
    } else {
        let correction = trailing_correction(below, here, upstream);
        (below + correction, correction < 0.0)
    }
}

/// Where edge `e` lies along its row, in cells from the row's first centre, +x
/// upstream.
fn edge_position(e: &ContactEdge, nx: usize) -> f64 {
    let i = (e.cell % nx) as f64;
    if e.is_leading() {
        i + e.theta
    } else {
        i - e.theta
    }
}

/// Whether `a` and `b` can be one edge in two solves: in the same row, both leading
/// or both trailing.
fn same_edge(a: &ContactEdge, b: &ContactEdge, nx: usize) -> bool {
    a.is_leading() == b.is_leading() && a.cell / nx == b.cell / nx
}

/// Whether an edge at `position` along the row of edge `e` (leading or trailing
/// as `e` is) would cut the same cell, theta in (0, 1].
fn within_cell_of(e: &ContactEdge, position: f64, nx: usize) -> bool {
    let offset = position - edge_position(e, nx);
    let theta = e.theta + if e.is_leading() { offset } else { -offset };
    theta > 0.0 && theta <= 1.0
}

/// The edges to solve with next, from the ones a solution used (`old`) and the ones
/// located on it (`new`), and whether they have settled: every entry cell of `old`
/// is still loaded, and each edge is where it was, in the same cell to
/// [`ENTRY_TOLERANCE`] (leading) or [`EXIT_TOLERANCE`] (trailing), across a
/// centre to [`CENTRE_CROSSING`], or swinging to and fro across one centre (below).
/// Settled edges keep their old place. An edge located across a centre moves there;
/// one that moved within its cell moves by [`RELOCATION_STEP`] of the way, or by a
/// secant step from the solve before (`previous`: its position along the row and
/// the one located on it), since the load it shifts moves the approach and, with
/// it, the other edges back.
fn next_edges(
    old: &[ContactEdge],
    previous: &[(f64, f64)],
    new: Vec<ContactEdge>,
    p: &[f64],
    nx: usize,
) -> (Vec<ContactEdge>, bool) {
    let position = |e: &ContactEdge| edge_position(e, nx);
    let matched = old.len() == new.len() && old.iter().zip(&new).all(|(a, b)| same_edge(a, b, nx));
    if !matched {
        return (new, false);
    }
    let mut settled = true;
    let edges = old
        .iter()
        .zip(new)
        .enumerate()
        .map(|(index, (a, b))| {
            let unloaded_entry = a.is_leading() && p[a.cell] <= 0.0;
            let shift = (position(a) - position(&b)).abs();
            if !unloaded_entry {
                let allowed = if a.cell != b.cell {
                    CENTRE_CROSSING
                } else if a.is_leading() {
                    ENTRY_TOLERANCE * a.theta.max(b.theta).max(ENTRY_FLOOR)
                } else {
                    EXIT_TOLERANCE
                };
                if shift <= allowed {
                    return *a;
                }
            }
            if a.cell != b.cell || unloaded_entry {
                let here = position(a);
                // An edge at a cell's centre: its located place jumps across the
                // centre as the cell loads and unloads, and no place between solves
                // (a full step alternated until the relocations ran out). Where the
                // edge swings back to the cell it came from, or was kept here last
                // time while located across by more than the allowance, it stays
                // put and counts as settled.
                let swinging = previous.get(index).is_some_and(|&(before, predicted)| {
                    let swings_back =
                        !within_cell_of(a, before, nx) && within_cell_of(&b, before, nx);
                    let kept = (here - before).abs() <= 1e-12
                        && (here - predicted).abs() > CENTRE_CROSSING
                        && within_cell_of(&b, predicted, nx);
                    swings_back || kept
                });
                if swinging {
                    return *a;
                }
                settled = false;
                return b;
            }
            settled = false;
            // A secant step on theta = prediction(theta) where the last solve's
            // edge was in this cell too, a damped step otherwise.
            let step = match previous.get(index) {
                Some(&(before, predicted))
                    if (position(a) - before).abs() > 1e-12
                        && within_cell_of(a, before, nx)
                        && within_cell_of(a, predicted, nx) =>
                {
                    let slope = (position(&b) - predicted) / (position(a) - before);
                    1.0 / (1.0 - slope.clamp(-3.0, 0.8))
                }
                _ => RELOCATION_STEP,
            };
            ContactEdge {
                theta: (a.theta + step * (b.theta - a.theta)).clamp(MIN_ENTRY, 1.0),
                ..b
            }
        })
        .collect();
    (edges, settled)
}

/// Cells per creep length over which trailing edges go from being placed by the
/// pressure's line (a lagging branch: the free gap has a kink there) to being placed
/// by the free gap, as leading edges are (a relaxed layer: the two ends alike, so
/// that their errors cancel in the friction, which is then small).
const TRAILING_CELLS: f64 = 10.0;

/// One Kelvin–Voigt branch on the grid.
#[derive(Debug, Clone, Copy)]
struct BranchStep {
    /// `C_k / C[0]`.
    scale: f64,
    /// `exp(-h / (V tau_k))`: what is left of the entering value over a cell.
    keep_full: f64,
    /// `1 - keep_full`.
    take_full: f64,
    /// `exp(-h / (2 V tau_k))`: the same over half a cell.
    keep_half: f64,
    /// `1 - keep_half`.
    take_half: f64,
    /// `(C_k / C[0]) g_half(h / (V tau_k)) / 2`: the centre value's response to the
    /// forcing's slope, per `F_upstream - F_downstream` (module docs).
    lag_half: f64,
    /// `(C_k / C[0]) g_full(h / (V tau_k)) / 2`: the same for the exit value.
    lag_full: f64,
    /// `h / (V tau_k)`.
    cells_per_creep_length: f64,
    /// `ramp_gain(h / (2 V tau_k))`, for the dissipated power.
    ramp_half: f64,
}

impl BranchStep {
    /// The work `int p dw` done on the branch over half a cell along which the
    /// pressure and the forcing `F` go linearly from `start` to `end` (each a
    /// `(p, F)`), with the branch's value `e` carried across it. The branch follows
    /// `L dw/ds = scale F(s) - w` (s along the path, `L = V tau`): over a length
    /// `l = y L` with `a = e^(-y)` and `df` the forcing's change, `w` leaves at
    /// `a e + (1 - a) f0 + df (1 - (1 - a) / y)`, and since `int w ds = int f ds - L
    /// (w_out - w_in)`, `int p dw = p0 dw + (p1 - p0) (w_out - mean f + dw / y)`.
    fn half_cell_work(&self, e: &mut f64, start: (f64, f64), end: (f64, f64)) -> f64 {
        let y = 0.5 * self.cells_per_creep_length;
        let gains = (self.keep_half, self.take_half, self.ramp_half);
        self.segment_work(e, start, end, y, gains)
    }

    /// [`Self::half_cell_work`] over `y` creep lengths, with `gains` =
    /// `(e^(-y), 1 - e^(-y), ramp_gain(y))`.
    fn segment_work(
        &self,
        e: &mut f64,
        start: (f64, f64),
        end: (f64, f64),
        y: f64,
        (keep, take, ramp): (f64, f64, f64),
    ) -> f64 {
        if y == 0.0 {
            return 0.0;
        }
        let (f0, f1) = (self.scale * start.1, self.scale * end.1);
        let out = keep * *e + take * f0 + (f1 - f0) * ramp;
        let moved = out - *e;
        let work = start.0 * moved + (end.0 - start.0) * (out - 0.5 * (f0 + f1) + moved / y);
        *e = out;
        work
    }

    /// The branch's response at the centre of a contact's entry cell to the forcing
    /// entering at `theta` cells upstream of the centre, `F_i + d (s - theta)` in
    /// cells `s` from the edge (`d` the forcing's change per cell along the path):
    /// `(1 - e^(-y)) F_i - d theta entry_lag(y)`, `y = theta h / (V tau)`, per unit
    /// of `C_k / C[0]`; as two coefficients `(of F_i, of d)`. Behind a rise (the
    /// forcing times `rho(s)`) less what the rise takes, [`Self::rise_deficit`]:
    /// `G0` of `F_i - d theta` and `theta G0 - H1` of `d`.
    fn entry_gains(&self, theta: f64, rise: Rise) -> (f64, f64) {
        let y = theta * self.cells_per_creep_length;
        let (of_forcing, of_slope) = (-(-y).exp_m1(), -theta * entry_lag(y));
        if rise.is_none() {
            (of_forcing, of_slope)
        } else {
            let (g0, h1) = self.rise_deficit(theta, rise_behind(rise, theta));
            (of_forcing - g0, of_slope + h1)
        }
    }

    /// What the rise takes from the branch over the half cell from an entry
    /// cell's centre (`theta` cells behind the edge) to its exit face, as the
    /// coefficients of `F_i` and `d` ([`Self::entry_gains`]): the deficit at the
    /// exit, `D(theta + 1/2)`, less what remains there of the one at the centre,
    /// with `D(s) = F_i G0(s) + d ((s - theta) G0(s) - H1(s))`.
    fn exit_deficit(&self, theta: f64, rise: Rise) -> (f64, f64) {
        if rise.is_none() {
            return (0.0, 0.0);
        }
        let rise = rise_behind(rise, theta);
        let (g0, h1) = self.rise_deficit(theta, rise);
        let (g0_exit, h1_exit) = self.rise_deficit(theta + 0.5, rise);
        (
            g0_exit - self.keep_half * g0,
            0.5 * g0_exit - h1_exit + self.keep_half * h1,
        )
    }

    /// What the rise takes from the branch `s` cells behind a leading edge, per unit
    /// of `C_k / C[0]`: with `x = h / (V tau)` and the forcing `(a + d s) rho(s)`,
    /// the branch started at zero is `x int_0^s e^(-x (s - u)) (a + d u) rho(u) du`,
    /// and the rise's part of it is `a G0 + d (s G0 - H1)`, per term `(a_m, l_m)` of
    /// the rise `G0 = a_m x int_0^s e^(-x v - (s - v) / l_m) dv` and `H1` the same
    /// with a factor v (v = s - u), summed. Each is `x` times an exponential times
    /// [`decaying_moments`] at the rate `|x - 1/l_m|`, written so that nothing
    /// overflows for any x (relaxed, `x = inf`: `G0 = a_m e^(-s / l_m)`, `H1 = 0`).
    fn rise_deficit(&self, s: f64, rise: Rise) -> (f64, f64) {
        self.rise_deficit_given(s, rise, &rise_decays(s, rise))
    }

    /// [`Self::rise_deficit`] given each term's `e^(-s / l_m)` ([`rise_decays`],
    /// shared by the branches at a quadrature node).
    fn rise_deficit_given(&self, s: f64, rise: Rise, decays: &[f64; RISE_TERMS]) -> (f64, f64) {
        let x = self.cells_per_creep_length;
        if x == 0.0 {
            return (0.0, 0.0);
        }
        let (mut g0, mut h1) = (0.0, 0.0);
        // e^(-x s) once for every term; each term's own decay e^(-s/l) then gives
        // the moments' e^(-|x - 1/l| s) as a ratio (where neither underflows).
        let branch_decay = if x.is_finite() { decay(x * s) } else { 0.0 };
        let terms = rise.amplitudes.iter().zip(&rise.lengths).zip(decays);
        for ((&amplitude, &l), &rise_decay) in terms {
            if amplitude == 0.0 || l <= 0.0 {
                continue;
            }
            let r = 1.0 / l;
            let (g, h) = if x.is_infinite() {
                (rise_decay, 0.0)
            } else if x >= r {
                // Over v: e^(-s/l) e^(-(x - 1/l) v).
                if rise_decay == 0.0 {
                    (0.0, 0.0)
                } else {
                    let rate = x - r;
                    let [m0, m1] = if branch_decay > 0.0 {
                        moments_with_decay(s, rate, branch_decay / rise_decay)
                    } else {
                        decaying_moments(s, rate)
                    };
                    let c = x * rise_decay;
                    (c * m0, c * m1)
                }
            } else if branch_decay == 0.0 {
                (0.0, 0.0)
            } else {
                // Over u = s - v: e^(-x s) e^(-(1/l - x) u).
                let [m0, m1] = moments_with_decay(s, r - x, rise_decay / branch_decay);
                let c = x * branch_decay;
                (c * m0, c * (s * m0 - m1))
            };
            g0 += amplitude * g;
            h1 += amplitude * h;
        }
        (g0, h1)
    }

    /// The branch `s` cells behind a leading edge where it held `start`, forced by
    /// `scale (a + d s)(1 - e^(-s / l))` ([`Self::rise_deficit`]).
    fn behind_rise(&self, start: f64, forcing: (f64, f64), s: f64, rise: Rise) -> f64 {
        self.behind_rise_given(start, forcing, s, rise, &rise_decays(s, rise))
    }

    /// [`Self::behind_rise`] given the rise's decays at `s` ([`rise_decays`]).
    fn behind_rise_given(
        &self,
        start: f64,
        (a, d): (f64, f64),
        s: f64,
        rise: Rise,
        decays: &[f64; RISE_TERMS],
    ) -> f64 {
        let y = s * self.cells_per_creep_length;
        let (g0, h1) = self.rise_deficit_given(s, rise, decays);
        let of_a = -(-y).exp_m1() - g0;
        let of_d = s * ramp_gain(y) - (s * g0 - h1);
        decay(y) * start + self.scale * (a * of_a + d * of_d)
    }

    /// The work `int p dw` done on the branch over the first `length` cells behind a
    /// leading edge, where pressure and forcing are their lines `(p_e + dp s)` and
    /// `(f_e + df s)` times the rise `rho(s)` (module docs), the branch entering at
    /// `e` and leaving with its value there. By parts, `p(length) w(length) - int w
    /// p' ds` (p is zero at the edge where the rise starts from zero; with a jump
    /// `p(0) w(0)` is subtracted too), the integral over `nodes` ([`RisingPath`],
    /// shared by the branches of a cell).
    fn rising_segment_work(&self, e: &mut f64, path: &RisingPath, forcing: (f64, f64)) -> f64 {
        let start = *e;
        let rise = path.rise;
        let integral: f64 = path
            .nodes
            .iter()
            .map(|node| {
                self.behind_rise_given(start, forcing, node.at, rise, &node.decays)
                    * node.weighted_slope
            })
            .sum();
        let end = self.behind_rise(start, forcing, path.length, rise);
        *e = end;
        let (pe, dp) = path.pressure;
        (pe + dp * path.length) * rise.share(path.length) * end
            - pe * rise.share(0.0) * start
            - integral
    }
}

/// `int_0^t s^n e^(-rate s) ds` for n = 0, 1 and `rate >= 0`: by their series
/// where `rate t <` [`SERIES_BELOW`] (no cancellation as the rate vanishes), else `m0 = (1 -
/// e^(-z)) / rate`, `m1 = (m0 - t e^(-z)) / rate`, `z = rate t`.
fn decaying_moments(t: f64, rate: f64) -> [f64; 2] {
    let z = rate * t;
    moments_with_decay(t, rate, if z < SERIES_BELOW { 1.0 } else { decay(z) })
}

/// [`decaying_moments`] given `e^(-rate t)` (used only where `rate t >=`
/// [`SERIES_BELOW`]).
fn moments_with_decay(t: f64, rate: f64, decay_at_t: f64) -> [f64; 2] {
    let z = rate * t;
    if z < SERIES_BELOW {
        // m0 = t sum (-z)^k / (k+1)!, m1 = t^2 sum (-z)^k / (k! (k+2)). The terms
        // fall by z / (k + 1) < 1/10 each: below 1e-17 of the sums within 16.
        let (mut term, mut s0, mut s1) = (1.0f64, 0.0, 0.0);
        for k in 0..16 {
            s0 += term * RECIPROCALS[k];
            s1 += term * RECIPROCALS[k + 1];
            term *= -z * RECIPROCALS[k];
            if term.abs() < 1e-17 {
                break;
            }
        }
        [t * s0, t * t * s1]
    } else {
        // 1 - e^(-z) loses at most a digit to cancellation for z >= 1/10.
        let m0 = (1.0 - decay_at_t) / rate;
        [m0, (m0 - t * decay_at_t) / rate]
    }
}

/// Where [`moments_with_decay`] sums its series: `rate t` below this.
const SERIES_BELOW: f64 = 0.1;

/// `1 / (k + 1)` for the moments' series (multiplications, not divisions, in a loop
/// that runs for every branch at every quadrature node).
const RECIPROCALS: [f64; 17] = {
    let mut r = [0.0; 17];
    let mut k = 0;
    while k < 17 {
        r[k] = 1.0 / (k as f64 + 1.0);
        k += 1;
    }
    r
};

/// `e^(-z)` for `z >= 0`, 0 beyond where it underflows (without the library's slow
/// path for results below the smallest normal double).
fn decay(z: f64) -> f64 {
    if z > 708.0 {
        0.0
    } else {
        (-z).exp()
    }
}

/// The quadrature of the branches' work behind a rise ([`BranchStep::rising_segment_work`]):
/// `int w p' ds` over the first `length` cells behind a leading edge, `p` the line
/// `(p_e + dp s)` times the rise, by Gauss–Legendre on panels that grow threefold
/// from an eighth of `shortest`, the shortest of the rise's lengths and the
/// branches' creep lengths (all may be far below the cell; panels growing fourfold
/// missed the RK4 reference by 4e-7, threefold and twofold agree with it to 1e-7).
/// `nodes` are the same for every branch of the cell.
struct RisingPath {
    rise: Rise,
    length: f64,
    pressure: (f64, f64),
    nodes: Vec<RisingNode>,
}

/// A node of [`RisingPath`]: its place, its weight times `p'` there and the rise's
/// decays there ([`rise_decays`]).
struct RisingNode {
    at: f64,
    weighted_slope: f64,
    decays: [f64; RISE_TERMS],
}

/// Each term's `e^(-s / l_m)` (0 for unused terms).
fn rise_decays(s: f64, rise: Rise) -> [f64; RISE_TERMS] {
    let mut decays = [0.0; RISE_TERMS];
    for ((d, &a), &l) in decays.iter_mut().zip(&rise.amplitudes).zip(&rise.lengths) {
        if a != 0.0 && l > 0.0 {
            *d = decay(s / l);
        }
    }
    decays
}

impl RisingPath {
    fn new(
        pressure: (f64, f64),
        length: f64,
        rise: Rise,
        shortest: f64,
        rule: &GaussLegendre,
    ) -> Self {
        let (pe, dp) = pressure;
        let slope = |s: f64, decays: &[f64; RISE_TERMS]| {
            let rate: f64 = (0..RISE_TERMS)
                .filter(|&m| rise.amplitudes[m] != 0.0 && rise.lengths[m] > 0.0)
                .map(|m| rise.amplitudes[m] * decays[m] / rise.lengths[m])
                .sum();
            dp * rise.share(s) + (pe + dp * s) * rate
        };
        let mut nodes = Vec::new();
        let mut lo = 0.0;
        let mut hi = (shortest / 8.0).min(length);
        loop {
            let (half, mid) = (0.5 * (hi - lo), 0.5 * (hi + lo));
            for (x, w) in rule.nodes.iter().zip(&rule.weights) {
                let at = mid + half * x;
                let decays = rise_decays(at, rise);
                nodes.push(RisingNode {
                    at,
                    weighted_slope: w * half * slope(at, &decays),
                    decays,
                });
            }
            if hi >= length {
                break;
            }
            lo = hi;
            hi = (3.0 * hi).min(length);
        }
        RisingPath {
            rise,
            length,
            pressure,
            nodes,
        }
    }
}

/// The shortest of the rise's lengths and the branches' creep lengths that move
/// (`1 / x` for finite x > 0), in cells: the scale of [`RisingPath`]'s first panel.
fn shortest_scale(rise: Rise, branches: &[BranchStep]) -> f64 {
    let mut shortest = rise.terms().map(|(_, l)| l).fold(f64::INFINITY, f64::min);
    for b in branches {
        let x = b.cells_per_creep_length;
        if x > 0.0 && x.is_finite() {
            shortest = shortest.min(1.0 / x);
        }
    }
    shortest
}

/// `sum_k b_k (C_k / C[0]) g_k`, `g_k` what branch k's exit value of an entry cell
/// gains per unit of its downstream neighbour's forcing ([`EntryGains::exit_gain`]):
/// the share of that neighbour's `J_ii` that reaches it through the entry cell.
fn entry_share(branches: &[BranchStep], gains: &[EntryGains]) -> f64 {
    branches
        .iter()
        .zip(gains)
        .map(|(b, g)| b.keep_half * b.scale * g.exit_gain(b))
        .sum()
}

/// The pressure's rise behind a located leading edge (module docs): in cells `s`
/// from the edge, with the interference growing linearly and the pressure reaching
/// `A` far behind, the layer `C_g p + sum_k w_k + F int_0^s p = F A s` (per unit of
/// `C[0]`, `F` the flow per cell, `L_k dw_k/ds + w_k = C_k p`, everything zero at
/// the edge) has, by Laplace's transform, `p = A (1 - sum_m a_m e^(-s / l_m))` with
/// `-1 / l_m` the roots of `g(q) = C_g q + sum_k C_k q / (1 + L_k q) + F` (one
/// between each pair of the branches' poles `-1 / L_k`, one above the slowest, and
/// one below the fastest where there is a glassy spring) and `a_m = -F / (q_m
/// g'(q_m))`, every one positive (`g' > 0`). Their sum is 1 with a glassy spring
/// (the pressure rises from zero), and `sum a_m l_m = (C_g + sum C_k) / F`: the
/// flow falls short by what the relaxed springs hold. One exponential, `l = C_g /
/// F`, without branches. Branches relaxed at once add to the glassy spring, frozen
/// ones nothing. More than [`RISE_TERMS`] terms are merged, neighbours in length,
/// each group into one with the same `sum a` and `sum a l`.
fn layer_rise(glassy: f64, flow_per_cell: f64, branches: &[BranchStep]) -> Rise {
    if flow_per_cell <= 0.0 {
        return Rise::NONE;
    }
    // Springs, and the moving branches as (x = 1 / L_k, C_k) by rising x.
    let mut springs = glassy;
    let mut moving: Vec<(f64, f64)> = Vec::new();
    for b in branches {
        let x = b.cells_per_creep_length;
        if x.is_infinite() {
            springs += b.scale;
        } else if x > 0.0 && b.scale > 0.0 {
            moving.push((x, b.scale));
        }
    }
    if moving.is_empty() {
        return Rise::single(springs / flow_per_cell);
    }
    moving.sort_by(|a, b| a.0.total_cmp(&b.0));
    moving.dedup_by(|later, kept| {
        let same = later.0 == kept.0;
        if same {
            kept.1 += later.1;
        }
        same
    });
    let g = |q: f64| {
        springs * q
            + moving
                .iter()
                .map(|&(x, c)| c * q * x / (x + q))
                .sum::<f64>()
            + flow_per_cell
    };
    let slope = |q: f64| {
        springs
            + moving
                .iter()
                .map(|&(x, c)| c * x * x / ((x + q) * (x + q)))
                .sum::<f64>()
    };
    // Brackets (lo, hi) of q on which g rises from -inf (or below zero) to +inf
    // (or above zero).
    let mut brackets = vec![(-moving[0].0, 0.0)];
    for pair in moving.windows(2) {
        brackets.push((-pair[1].0, -pair[0].0));
    }
    if springs > 0.0 {
        // Below the fastest pole each branch's term lies in (C x, 2 C x) once q <
        // -2 x: the root is above -(2 sum C x + F) / C_g.
        let fastest = moving[moving.len() - 1].0;
        let reach: f64 = moving.iter().map(|&(x, c)| 2.0 * c * x).sum::<f64>() + flow_per_cell;
        brackets.push(((-2.0 * fastest).min(-reach / springs), -fastest));
    }
    let mut terms: Vec<(f64, f64)> = brackets
        .into_iter()
        .map(|(lo, hi)| {
            let q = increasing_root(&g, &slope, lo, hi);
            (-flow_per_cell / (q * slope(q)), -1.0 / q)
        })
        .collect();
    // Merge neighbours in length into RISE_TERMS groups.
    terms.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut rise = Rise::NONE;
    let n = terms.len();
    for m in 0..RISE_TERMS.min(n) {
        let group = &terms[m * n / RISE_TERMS.min(n)..(m + 1) * n / RISE_TERMS.min(n)];
        let amplitude: f64 = group.iter().map(|t| t.0).sum();
        let deficit: f64 = group.iter().map(|t| t.0 * t.1).sum();
        rise.amplitudes[m] = amplitude;
        rise.lengths[m] = deficit / amplitude;
    }
    rise
}

/// The root of `g`, increasing on the open interval `(lo, hi)` (a pole or the
/// bracket's end at each side), by Newton's method kept inside the bracket by
/// bisection (written here: a dozen lines for a monotone function with a known
/// bracket).
fn increasing_root(g: &impl Fn(f64) -> f64, slope: &impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    let mut q = 0.5 * (lo + hi);
    for _ in 0..200 {
        let value = g(q);
        if value > 0.0 {
            hi = q;
        } else {
            lo = q;
        }
        let step = value / slope(q);
        let next = q - step;
        let next = if next > lo && next < hi && step.is_finite() {
            next
        } else {
            0.5 * (lo + hi)
        };
        if (next - q).abs() <= 1e-15 * q.abs() || hi - lo <= 1e-15 * q.abs() {
            return next;
        }
        q = next;
    }
    q
}

/// What the flow of an entry cell at `theta` passes downstream, per unit of its own
/// creep rate and of its downstream neighbour's: the creep rate integrated from the
/// edge over the cell, linear through the two centres times `rise` behind the
/// edge (the cell's mean pressure, [`ContactEdge::mean_weights`]; constant without
/// a neighbour).
fn entry_flow_weights(theta: f64, has_neighbour: bool, rise: Rise) -> (f64, f64) {
    entry_edge(theta, has_neighbour, rise).mean_weights()
}

/// An entry cell's edge, for its weights (the cell and neighbour indices are not
/// used), its rise [`rise_behind`] the edge.
fn entry_edge(theta: f64, has_neighbour: bool, rise: Rise) -> ContactEdge {
    ContactEdge {
        cell: 1,
        neighbour: has_neighbour.then_some(0),
        theta,
        rise: rise_behind(rise, theta),
    }
}

/// Least distance from a leading edge to its cell's centre, in lengths of the rise
/// behind it: nearer, the rise's lengths are shortened to `theta /
/// CENTRE_IN_RISE`.
const CENTRE_IN_RISE: f64 = 0.1;

/// The rise behind an edge `theta` cells from its cell's centre, of the layer's
/// `rise`: that, each length at most `theta / CENTRE_IN_RISE`. The cell's centre
/// value is fixed by the contact condition at its centre, which sees the pressure
/// there, `rho(theta)` of it. Where the free gap closes at or past the centre
/// (theta held at [`MIN_ENTRY`] while the cell stays loaded) that share vanishes,
/// nothing fixes the load the cell carries behind its centre, and the solution
/// followed the body's smallest changes (a film 8e-6 thick on the body moved one
/// cell by 5e-3 of the peak, 27 times the film's effect elsewhere). The shortened
/// rise keeps the share at `1 - e^(-1/10)` or more (the film's effect: 2e-4); a
/// quarter instead of a tenth gave up to 7 % on the peak of rows whose edges lie
/// near a centre, a tenth and a thirtieth within 1.1 % of the rigid-base closed
/// form.
fn rise_behind(rise: Rise, theta: f64) -> Rise {
    rise.shortened(theta / CENTRE_IN_RISE)
}

/// The flow at an entry cell's centre, per unit of its own creep rate and of its
/// downstream neighbour's: the rate integrated from the edge over `theta` cells,
/// linear through the two centres, `theta q_i - theta^2 (q_{i-1} - q_i) / 2`
/// (constant without a neighbour), less what the rise takes
/// ([`ContactEdge::rise_deficit`]).
fn entry_centre_weights(theta: f64, has_neighbour: bool, rise: Rise) -> (f64, f64) {
    let (a, b) = if has_neighbour {
        let half_square = 0.5 * theta * theta;
        (theta + half_square, -half_square)
    } else {
        (theta, 0.0)
    };
    let (da, db) = entry_edge(theta, has_neighbour, rise).rise_deficit(theta);
    (a - da, b - db)
}

/// `(1 - e^(-y) (1 + y)) / y`: a branch started at zero and driven over `y` creep
/// lengths by a forcing that rises by 1 per creep length, less the same forcing's
/// final value times `1 - e^(-y)`, changes sign: this is what it lags behind (`y/2`
/// for small y, `1/y` for large y, 0 at both ends).
fn entry_lag(y: f64) -> f64 {
    if y < 1e-3 {
        y * (0.5 - y * (1.0 / 3.0 - y / 8.0))
    } else if y.is_infinite() {
        0.0
    } else {
        (1.0 - (-y).exp() * (1.0 + y)) / y
    }
}

/// `1 - (1 - e^(-y)) / y`: what a branch gains from a forcing rising by 1 over `y`
/// creep lengths (`y/2` for small y, `1 - 1/y` for large y).
fn ramp_gain(y: f64) -> f64 {
    if y < 1e-3 {
        y * (0.5 - y * (1.0 / 6.0 - y / 24.0))
    } else {
        1.0 + (-y).exp_m1() / y
    }
}

/// Where a cell is shorter than a tenth of the creep length the cell-wise constant
/// forcing is already of second order and the centred slope, which couples a cell
/// to its downstream neighbour, would undamp the odd-even mode of a Kelvin–Voigt
/// leading edge: the slope is kept in the share `1 - exp(-(10 h / (V tau))^2)`
/// (1 to 1e-4 once the cell exceeds a third of the creep length, 0.63 at a tenth,
/// 1e-4 at a hundredth).
fn slope_weight(x: f64) -> f64 {
    -(-(10.0 * x) * (10.0 * x)).exp_m1()
}

/// `g_half(x) = (1 - e^(-x/2)) / x - e^(-x/2) / 2`: the centre value of a branch
/// driven by a forcing of unit slope (per cell) over the upstream half of a cell of
/// `x = h / (V tau)` creep lengths, less its value without the slope. `x/8` for
/// small x, `1/x` for large x (the lag `V tau dF/dx`); 0 at both ends of the range.
fn lag_at_centre(x: f64) -> f64 {
    if x < 1e-3 {
        x * (1.0 / 8.0 - x * (1.0 / 24.0 - x / 128.0))
    } else {
        let b = (-0.5 * x).exp();
        -(-0.5 * x).exp_m1() / x - 0.5 * b
    }
}

/// `g_full(x) = (1 - e^(-x)) / x - (1 + e^(-x)) / 2`: the same at a cell's exit
/// (`-x^2/12` for small x, `1/x - 1/2` for large x).
fn lag_at_exit(x: f64) -> f64 {
    if x < 1e-3 {
        -x * x * (1.0 / 12.0 - x * (1.0 / 24.0 - x / 80.0))
    } else {
        let a = (-x).exp();
        -(-x).exp_m1() / x - 0.5 * (1.0 + a)
    }
}

/// A layer of the creep form on a grid's rows: the row sweep and its linearisation.
#[derive(Debug, Clone)]
pub struct ViscoelasticRows {
    layer: Layer,
    nx: usize,
    ny: usize,
    /// The extent of a row along y: the cell's side `h` (a point contact's rows),
    /// or 1 for a line contact's one row (forces per unit length).
    row_length: f64,
    /// `C[0]` of the law the parts are scaled against.
    reference: f64,
    /// `C_g / C[0]`.
    glassy_scale: f64,
    /// `(C_v / C[0]) h / (V T)`: flow per cell of path, 0 for no flow or infinite V.
    flow_per_cell: f64,
    /// The length over which the pressure rises behind a located leading edge
    /// ([`ContactEdge::rise`]).
    rise: Rise,
    /// The Gauss–Legendre rule of the branches' work behind a rise
    /// ([`BranchStep::rising_segment_work`]).
    rule: GaussLegendre,
    /// The flow's upwind share ([`flow_upwind_share`]).
    flow_upwind: f64,
    branches: Vec<BranchStep>,
    /// `kappa s sum_k (b_k - a_k) C_k / C[0]`: the upwind correction's weight.
    upwind: f64,
    /// `sum_k (1 - b_k) C_k / C[0]`: the branches' own response over half a cell.
    branch_own: f64,
    /// `sum_k lag_half_k`: the centre value's response to `F_upstream - F_downstream`.
    lag_half: f64,
    /// How the row passes are split over threads.
    passes: Passes,
    /// Per cell, where a contact enters it: `theta` in (0, 1] for a loaded cell
    /// whose upstream neighbour is not, the distance from the edge to the cell's
    /// centre in cells; 0 elsewhere (empty: no entries located yet).
    entries: Vec<f64>,
    /// The same entries as a list.
    edge_list: Vec<ContactEdge>,
    /// Per edge of `edge_list`, its position along its row in the solve before and
    /// the position located on that solve (NaN where the two are not the same
    /// edge): the relocation's secant steps.
    edge_history: Vec<(f64, f64)>,
    /// Whether the contacts' edges are placed inside their cells: some branch moves
    /// and carries something across a cell (not frozen, V = inf; not relaxed within
    /// a cell to the last double).
    locates_edges: bool,
    /// The share of a trailing edge placed by the pressure's line (the rest by the
    /// free gap, as leading edges are): `sum_k C_k e^(-h / (V tau_k TRAILING_CELLS))
    /// / sum_k C_k` (module docs).
    trailing_by_pressure: f64,
}

impl ViscoelasticRows {
    /// The layer on rows of `nx` cells of side `cell`, sliding at `velocity`.
    pub fn new(layer: Layer, nx: usize, ny: usize, cell: f64, velocity: f64) -> Self {
        let form: CreepForm = layer.rheology.creep_form();
        let reference = layer.reference_compliance();
        let flow_per_cell = match form.flow {
            Some(Flow { compliance, time }) if velocity.is_finite() => {
                (compliance / reference) * (cell / (velocity * time))
            }
            _ => 0.0,
        };
        let branches = form
            .branches
            .iter()
            .map(|b| {
                // h / (V tau): 0 for infinite V (the branch has no time to move),
                // +inf when it relaxes within a cell.
                let x = cell / (velocity * b.time);
                let scale = b.compliance / reference;
                BranchStep {
                    scale,
                    keep_full: (-x).exp(),
                    take_full: -(-x).exp_m1(),
                    keep_half: (-0.5 * x).exp(),
                    take_half: -(-0.5 * x).exp_m1(),
                    lag_half: 0.5 * scale * slope_weight(x) * lag_at_centre(x),
                    lag_full: 0.5 * scale * slope_weight(x) * lag_at_exit(x),
                    ramp_half: ramp_gain(0.5 * x),
                    cells_per_creep_length: x,
                }
            })
            .collect::<Vec<BranchStep>>();
        let glassy_scale = form.glassy / reference;
        let branch_own: f64 = branches.iter().map(|b| b.take_half * b.scale).sum();
        let share = if branch_own > 0.0 {
            branch_own / (glassy_scale + branch_own)
        } else {
            0.0
        };
        // The damping is faded out as cells grow longer than the creep length
        // (e^(-2h / (V tau))), where it would bias the lag the slope carries.
        let upwind = UPWIND
            * share
            * branches
                .iter()
                .map(|b| {
                    (b.keep_half - b.keep_full) * (-2.0 * b.cells_per_creep_length).exp() * b.scale
                })
                .sum::<f64>();
        let lag_half = branches.iter().map(|b| b.lag_half).sum();
        let springs = glassy_scale + branch_own;
        let flow_upwind = if flow_per_cell > 0.0 {
            flow_upwind_share(flow_per_cell / springs)
        } else {
            0.0
        };
        let flow_places_edges = 0.5 * flow_per_cell
            > FLOW_EDGE_SHARE * (glassy_scale + branch_own + 0.5 * flow_per_cell);
        let rise = if flow_places_edges {
            layer_rise(glassy_scale, flow_per_cell, &branches)
        } else {
            Rise::NONE
        };
        ViscoelasticRows {
            flow_upwind,
            rise,
            rule: GaussLegendre::new(8),
            entries: Vec::new(),
            edge_list: Vec::new(),
            edge_history: Vec::new(),
            // The flow places edges where a cell of it exceeds the springs'
            // response ([`FLOW_EDGE_SHARE`]).
            locates_edges: flow_places_edges
                || branches
                    .iter()
                    .filter(|b| b.cells_per_creep_length > 0.0 && b.keep_half > 0.0)
                    .map(|b| b.take_half * b.scale)
                    .sum::<f64>()
                    > MOVING_BRANCH_SHARE * (glassy_scale + branch_own),
            trailing_by_pressure: {
                let total: f64 = branches.iter().map(|b| b.scale).sum();
                let lagging: f64 = branches
                    .iter()
                    .map(|b| b.scale * (-b.cells_per_creep_length / TRAILING_CELLS).exp())
                    .sum();
                if total > 0.0 {
                    lagging / total
                } else {
                    0.0
                }
            },
            lag_half,
            upwind,
            branch_own,
            passes: Passes::new(nx * ny, Parallelism::Rayon),
            glassy_scale,
            layer,
            nx,
            ny,
            row_length: cell,
            reference,
            flow_per_cell,
            branches,
        }
    }

    /// The same rows, each `length` long along y (a line contact's one row: 1).
    pub fn with_row_length(mut self, length: f64) -> Self {
        self.row_length = length;
        self
    }

    /// Splits the row passes over the rayon pool only when `parallelism` asks for it
    /// and the grid has at least `PARALLEL_MIN_CELLS` cells (the default asks for
    /// it), by the rules of the solvers' passes.
    pub fn with_parallelism(mut self, parallelism: Parallelism) -> Self {
        self.passes = Passes::new(self.nx * self.ny, parallelism);
        self
    }

    /// The layer.
    pub fn layer(&self) -> &Layer {
        &self.layer
    }

    /// The forcing `F(p)` of the elastic parts (`G(p)` or `C[p] p`) and `dF/dp`, and
    /// the flow's rate density `C[p] p` and its derivative, from one evaluation of
    /// the law (the costly part of every row pass).
    fn forcing_and_creep(&self, p: f64) -> ((f64, f64), (f64, f64)) {
        let l = self.layer.law.at(self.reference, p);
        let creep = (l.compliance * p, l.compliance + l.slope * p.max(0.0));
        let forcing = match self.layer.integration {
            Integration::Exact => (l.integral, l.compliance),
            Integration::Secant => creep,
        };
        (forcing, creep)
    }

    /// The forcing and its derivative alone (tests).
    #[cfg(test)]
    fn forcing(&self, p: f64) -> (f64, f64) {
        self.forcing_and_creep(p).0
    }

    /// The flow's rate density and its derivative alone (tests).
    #[cfg(test)]
    fn creep(&self, p: f64) -> (f64, f64) {
        self.forcing_and_creep(p).1
    }

    /// Layer displacement `w3` of every cell: one sweep per row from the leading edge.
    pub fn row_sweep(&self, p: &[f64], w3: &mut [f64]) {
        // Rows are independent: one per task, each with its own branch states.
        let rows = p
            .par_chunks_exact(self.nx)
            .zip(w3.par_chunks_exact_mut(self.nx))
            .enumerate()
            .with_min_len(self.passes.min_rows(self.nx));
        rows.for_each_init(
            || vec![0.0; self.branches.len()],
            |state, (r, (prow, wrow))| self.sweep_row(prow, self.row_entries(r), state, wrow, None),
        );
    }

    /// The entry fractions of row `r` (empty when the layer has none).
    fn row_entries(&self, r: usize) -> &[f64] {
        if self.entries.is_empty() {
            &[]
        } else {
            &self.entries[r * self.nx..(r + 1) * self.nx]
        }
    }

    /// One row of [`Self::row_sweep`]; `free`, if given, receives what each cell's
    /// displacement would be at zero pressure in that cell alone (the flow and the
    /// branches carried in from upstream).
    fn sweep_row(
        &self,
        prow: &[f64],
        entries: &[f64],
        state: &mut [f64],
        wrow: &mut [f64],
        mut free: Option<&mut [f64]>,
    ) {
        let nx = self.nx;
        let entry = |i: usize| entries.get(i).copied().unwrap_or(0.0);
        let mut upstream = 0.0;
        let mut upstream_forcing = 0.0;
        let mut upstream_creep = 0.0;
        state.fill(0.0);
        // The cell's forcing and creep rate, and the downstream cell's forcing (the
        // slope of the forcing is centred), each law evaluation done once per cell.
        let mut here = self.forcing_and_creep(prow[nx - 1]);
        for i in (0..nx).rev() {
            let ((f, _), (q, _)) = here;
            if i > 0 {
                here = self.forcing_and_creep(prow[i - 1]);
            }
            let next_forcing = if i > 0 { here.0 .0 } else { 0.0 };
            if let Some(free) = free.as_deref_mut() {
                let carried: f64 = self
                    .branches
                    .iter()
                    .zip(state.iter())
                    .map(|(b, e)| b.keep_half * e)
                    .sum();
                free[i] =
                    self.flow_per_cell * (upstream - self.flow_upwind * upstream_creep) + carried;
            }
            let theta = entry(i);
            let rise = if theta > 0.0 { self.rise } else { Rise::NONE };
            let mut retarded = 0.0;
            // The flow's centre value, and what the cell passes downstream (module
            // docs: from a located edge, the creep rate linear through the
            // downstream neighbour's).
            let (flow, passed) = if theta > 0.0 {
                let next_creep = if i > 0 { here.1 .0 } else { q };
                let (a, b) = entry_flow_weights(theta, i > 0, rise);
                let centre = if !rise.is_none() {
                    let (ca, cb) = entry_centre_weights(theta, i > 0, rise);
                    ca * q + cb * next_creep
                } else {
                    // `entry_centre_weights` (the Jacobian's) applied, written so
                    // that the recorded results keep their last bits.
                    theta * q - 0.5 * theta * theta * (next_creep - q)
                };
                (upstream + centre, a * q + b * next_creep)
            } else {
                let correction = self.flow_upwind * (q - upstream_creep);
                (upstream + 0.5 * q + correction, q)
            };
            if theta > 0.0 {
                // A contact's entry cell: the branches are forced from the edge on.
                let d = next_forcing - f;
                for (b, e) in self.branches.iter().zip(state.iter_mut()) {
                    let (of_forcing, of_slope) = b.entry_gains(theta, rise);
                    let centre = b.keep_half * *e + b.scale * (of_forcing * f + of_slope * d);
                    retarded += centre;
                    *e = b.keep_half * centre + b.scale * (b.take_half * f + 0.5 * d * b.ramp_half);
                    if !rise.is_none() {
                        // The rise goes on past the centre.
                        let (xf, xd) = b.exit_deficit(theta, rise);
                        *e -= b.scale * (xf * f + xd * d);
                    }
                }
            } else {
                let entry_below = if i > 0 { entry(i - 1) } else { 0.0 };
                let (downstream_forcing, _) =
                    slope_downstream(i, entry_below, next_forcing, f, upstream_forcing);
                let rise = upstream_forcing - downstream_forcing;
                for (b, e) in self.branches.iter().zip(state.iter_mut()) {
                    let force = b.scale * f;
                    retarded += b.keep_half * *e + b.take_half * force;
                    *e = b.keep_full * *e + b.take_full * force + b.lag_full * rise;
                }
                if !self.branches.is_empty() {
                    retarded += self.upwind * (f - upstream_forcing) + self.lag_half * rise;
                }
            }
            // Behind a rising edge the glassy spring takes the pressure at the
            // centre, a share of the centre value.
            let glassy = if !rise.is_none() {
                self.glassy_scale * entry_edge(theta, i > 0, rise).centre_share()
            } else {
                self.glassy_scale
            };
            wrow[i] = glassy * f + self.flow_per_cell * flow + retarded;
            upstream += passed;
            upstream_forcing = f;
            upstream_creep = q;
        }
    }

    /// One row's dissipated energy per unit area of path (see
    /// [`Self::dissipated_force`]).
    fn row_dissipation(&self, prow: &[f64], entries: &[f64], state: &mut [f64]) -> f64 {
        let entry = |i: usize| entries.get(i).copied().unwrap_or(0.0);
        state.fill(0.0);
        let mut row = 0.0;
        let n = self.nx;
        // Pressure and forcing at the upstream face (the mean of the two cells, or
        // half the cell's at the window's edge).
        let mut upstream = (0.0, 0.0);
        let mut here = self.forcing_and_creep(prow[n - 1]);
        for i in (0..n).rev() {
            let ((f, _), (q, _)) = here;
            let p = prow[i];
            let downstream = if i > 0 {
                here = self.forcing_and_creep(prow[i - 1]);
                (prow[i - 1], here.0 .0)
            } else {
                (0.0, 0.0)
            };
            let theta = entry(i);
            let rise = if theta > 0.0 {
                rise_behind(self.rise, theta)
            } else {
                Rise::NONE
            };
            if !rise.is_none() {
                // Behind a rising edge pressure and creep rate are both their line
                // times `rho(s) = 1 - sum_m a_m e^(-s / l_m)` (module docs): the
                // product's line times `rho^2 = 1 - 2 sum_m a_m e^(-s / l_m) + sum_mn
                // a_m a_n e^(-s (1/l_m + 1/l_n))`, integrated over the loaded part.
                let (dp, dq) = if i > 0 {
                    (downstream.0 - p, here.1 .0 - q)
                } else {
                    (0.0, 0.0)
                };
                let x = theta + 0.5;
                let (ap, aq) = (p - theta * dp, q - theta * dq);
                let line = [ap * aq, ap * dq + aq * dp, dp * dq];
                let (mut once, mut twice) = ([0.0; 3], [0.0; 3]);
                for (a, l) in rise.terms() {
                    let m = exponential_moments(x, l);
                    for n in 0..3 {
                        once[n] += a * m[n];
                    }
                    for (b, k) in rise.terms() {
                        let both = if k == l { 0.5 * l } else { l * k / (l + k) };
                        let m = exponential_moments(x, both);
                        for n in 0..3 {
                            twice[n] += a * b * m[n];
                        }
                    }
                }
                let full = [x, 0.5 * x * x, x * x * x / 3.0];
                let work: f64 = (0..3)
                    .map(|n| line[n] * (full[n] - 2.0 * once[n] + twice[n]))
                    .sum();
                row += self.flow_per_cell * work;
            } else {
                row += self.flow_per_cell
                    * if theta > 0.0 && i > 0 {
                        // From the edge, pressure and creep rate linear through the
                        // downstream centre: int (p + dp u)(q + dq u) du over
                        // u in (-theta, 1/2).
                        let (dp, dq) = (downstream.0 - p, here.1 .0 - q);
                        let first = 0.5 * (0.25 - theta * theta);
                        let second = (0.125 + theta * theta * theta) / 3.0;
                        p * q * (theta + 0.5) + (p * dq + q * dp) * first + dp * dq * second
                    } else if theta > 0.0 {
                        p * q * (theta + 0.5)
                    } else {
                        p * q
                    };
            }
            if !self.branches.is_empty() {
                let exit = (0.5 * (p + downstream.0), 0.5 * (f + downstream.1));
                if theta > 0.0 {
                    // Free relaxation from the upstream centre to the edge, then the
                    // loaded part of the cell, reconstructed linearly through the
                    // downstream neighbour (as the displacement is).
                    let edge = (
                        p - theta * (downstream.0 - p),
                        f - theta * (downstream.1 - f),
                    );
                    let lines = ((edge.0, downstream.0 - p), (edge.1, downstream.1 - f));
                    // Behind a rise, the branches' work to the exit face on nodes
                    // they share.
                    let path = (!rise.is_none()).then(|| {
                        let shortest = shortest_scale(rise, &self.branches);
                        RisingPath::new(lines.0, theta + 0.5, rise, shortest, &self.rule)
                    });
                    for (b, e) in self.branches.iter().zip(state.iter_mut()) {
                        let free = (1.0 - theta) * b.cells_per_creep_length;
                        if free > 0.0 {
                            *e *= (-free).exp();
                        }
                        if let Some(path) = &path {
                            // Behind the rise to the exit face, as the centre and
                            // exit values are.
                            row += b.rising_segment_work(e, path, lines.1);
                        } else {
                            let y = theta * b.cells_per_creep_length;
                            let gains = ((-y).exp(), -(-y).exp_m1(), ramp_gain(y));
                            row += b.segment_work(e, edge, (p, f), y, gains);
                            row += b.half_cell_work(e, (p, f), exit);
                        }
                    }
                } else {
                    let entry_half = (0.5 * (upstream.0 + p), 0.5 * (upstream.1 + f));
                    // Upstream of an entry cell nothing is loaded past the centre;
                    // the entry cell carries the branches on from this centre.
                    let before_entry = i > 0 && entry(i - 1) > 0.0;
                    for (b, e) in self.branches.iter().zip(state.iter_mut()) {
                        row += b.half_cell_work(e, entry_half, (p, f));
                        if !before_entry {
                            row += b.half_cell_work(e, (p, f), exit);
                        }
                    }
                }
            }
            upstream = (p, f);
        }
        row
    }

    /// The power dissipated in the layer divided by the sliding speed (a force:
    /// divided by the normal load it is a friction coefficient), by the exact
    /// integration over each cell in the module docs; the branches' relaxation
    /// downstream of the window is included. Zero for an infinite velocity.
    pub fn dissipated_force(&self, p: &[f64]) -> f64 {
        // Rows in parallel, their sums added in row order (the same bits on any
        // number of threads).
        let rows: Vec<f64> = p
            .par_chunks(self.nx)
            .enumerate()
            .with_min_len(self.passes.min_rows(self.nx))
            .map_init(
                || vec![0.0; self.branches.len()],
                |state, (r, prow)| self.row_dissipation(prow, self.row_entries(r), state),
            )
            .collect();
        let total: f64 = rows.iter().fold(0.0, |t, r| t + r);
        // Each cell's term is the energy per unit area dissipated while material
        // crosses it; a row of width h (a line contact's: of unit length) carries
        // h V of area per unit time.
        total * self.row_length
    }

    /// The linearisation at a pressure field, for Newton steps.
    pub fn jacobian(&self, p: &[f64]) -> ViscoelasticJacobian {
        let n = p.len();
        let lag_self: f64 = self.branches.iter().map(|b| b.keep_half * b.lag_full).sum();
        let mut diagonal = vec![0.0; n];
        let mut flow_slope = vec![0.0; n];
        let mut forcing_slope = vec![0.0; n];
        let mut forcing = vec![0.0; n];
        // Cell by cell (the law's evaluations are the cost), in chunks.
        diagonal
            .par_chunks_mut(CHUNK)
            .zip(flow_slope.par_chunks_mut(CHUNK))
            .zip(forcing_slope.par_chunks_mut(CHUNK))
            .zip(forcing.par_chunks_mut(CHUNK))
            .zip(p.par_chunks(CHUNK))
            .with_min_len(self.passes.min_len())
            .for_each(|((((diagonal, flow_slope), forcing_slope), forcing), p)| {
                for (k, &pk) in p.iter().enumerate() {
                    let ((f, df), (_, dq)) = self.forcing_and_creep(pk);
                    forcing[k] = f;
                    flow_slope[k] = self.flow_per_cell * dq;
                    forcing_slope[k] = df;
                    let retarded = self.branch_own * df;
                    diagonal[k] = self.glassy_scale * df
                        + (0.5 + self.flow_upwind) * flow_slope[k]
                        + retarded
                        + self.upwind * df;
                    if lag_self != 0.0 {
                        // The upstream cell's exit value falls with this cell's
                        // forcing (the centred slope there), and reaches the centre.
                        diagonal[k] -= lag_self * df;
                    }
                }
            });
        if lag_self != 0.0 {
            // The leading cell of each row has no upstream cell.
            for k in (self.nx - 1..n).step_by(self.nx) {
                diagonal[k] += lag_self * forcing_slope[k];
            }
        }
        let entries = if self.entries.len() == n {
            self.entries.clone()
        } else {
            Vec::new()
        };
        // Each entry cell's branch gains, once per linearisation rather than once
        // per product (with a rise each costs a few exponentials per branch).
        let mut entry_slots = vec![u32::MAX; entries.len()];
        let mut entry_gains = Vec::new();
        for (k, &theta) in entries.iter().enumerate() {
            if theta > 0.0 {
                entry_slots[k] = (entry_gains.len() / self.branches.len().max(1)) as u32;
                entry_gains.extend(
                    self.branches
                        .iter()
                        .map(|b| EntryGains::new(b, theta, self.rise)),
                );
            }
        }
        for (k, &theta) in entries.iter().enumerate() {
            if theta <= 0.0 {
                continue;
            }
            // An entry cell's branches are forced from the edge only; the cell
            // downstream of it gets the entry's exit value's share instead of the
            // centred slope's.
            let ((_, df), (_, dq)) = self.forcing_and_creep(p[k]);
            let rise = self.rise;
            let n = self.branches.len();
            let slot = entry_slots[k] as usize;
            let gains = &entry_gains[slot * n..(slot + 1) * n];
            let own: f64 = self
                .branches
                .iter()
                .zip(gains)
                .map(|(b, g)| b.scale * (g.of_forcing - g.of_slope))
                .sum();
            // The flow from the edge: `theta q_k - theta^2 (q_{k-1} - q_k) / 2` at
            // the centre, `b q_{k-1}` of what it passes on reaching the downstream
            // neighbour's own centre value.
            let neighbour = k % self.nx > 0;
            let flow_own = entry_centre_weights(theta, neighbour, rise).0;
            let glassy = self.glassy_scale * entry_edge(theta, neighbour, rise).centre_share();
            diagonal[k] = (glassy + own) * df + flow_own * self.flow_per_cell * dq;
            if neighbour {
                diagonal[k - 1] +=
                    (lag_self + entry_share(&self.branches, gains)) * forcing_slope[k - 1];
                diagonal[k - 1] += entry_flow_weights(theta, true, rise).1 * flow_slope[k - 1];
            }
        }
        // Cells whose slope takes the trailing correction (`slope_downstream`, as
        // in the sweep; entry cells have no slope term). There the
        // slope's downstream forcing is `2 F_{i-1} + 2 F_i - F_{i+1}`: the cell's
        // own forcing enters its centre value through `- 2 lag_half`, and the
        // downstream neighbour's enters this cell's exit value twice.
        let trailing: Vec<bool> = if self.branches.is_empty() {
            Vec::new()
        } else {
            (0..n)
                .map(|k| {
                    let i = k % self.nx;
                    // (`p` may be shorter than a row: the self-compliance's one cell.)
                    let upstream = if i + 1 < self.nx && k + 1 < n {
                        forcing[k + 1]
                    } else {
                        0.0
                    };
                    let (entry_below, below) = if i > 0 {
                        (entries.get(k - 1).copied().unwrap_or(0.0), forcing[k - 1])
                    } else {
                        (0.0, 0.0)
                    };
                    entries.get(k).copied().unwrap_or(0.0) <= 0.0
                        && slope_downstream(i, entry_below, below, forcing[k], upstream).1
                })
                .collect()
        };
        for k in (0..trailing.len()).filter(|&k| trailing[k]) {
            diagonal[k] -= 2.0 * self.lag_half * forcing_slope[k];
            diagonal[k - 1] -= lag_self * forcing_slope[k - 1];
        }
        ViscoelasticJacobian {
            flow_upwind: self.flow_upwind,
            rise: self.rise,
            entries,
            trailing,
            entry_slots,
            entry_gains,
            branches: self.branches.clone(),
            min_rows: self.passes.min_rows(self.nx),
            upwind: self.upwind,
            nx: self.nx,
            diagonal,
            flow_slope,
            forcing_slope,
            keep_half: self.branches.iter().map(|b| b.keep_half).collect(),
            keep_full: self.branches.iter().map(|b| b.keep_full).collect(),
            take_full_scaled: self
                .branches
                .iter()
                .map(|b| b.take_full * b.scale)
                .collect(),
            lag_full: self.branches.iter().map(|b| b.lag_full).collect(),
            lag_half: self.lag_half,
            lag_self,
        }
    }

    /// Where each contact enters its first loaded cell (module docs), from a
    /// solution's pressure and gap; `None` for a layer without branches.
    fn entries_of(&self, p: &[f64], gap: &[f64]) -> Option<(Vec<f64>, Vec<f64>)> {
        if !self.locates_edges || p.len() != self.nx * self.ny || gap.len() != p.len() {
            return None;
        }
        let nx = self.nx;
        let mut entries = vec![0.0; p.len()];
        let mut exits = vec![0.0; p.len()];
        entries
            .par_chunks_mut(nx)
            .zip(exits.par_chunks_mut(nx))
            .zip(p.par_chunks(nx).zip(gap.par_chunks(nx)))
            .enumerate()
            .with_min_len(self.passes.min_rows(nx))
            .for_each_init(
                || (vec![0.0; self.branches.len()], vec![0.0; nx], vec![0.0; nx]),
                |(state, w, free), (r, ((theta, exit), (prow, grow)))| {
                    self.sweep_row(prow, self.row_entries(r), state, w, Some(free));
                    // The free gap (the gap less the layer's response to the cell's own
                    // load) closes between an open centre and the loaded one next to it:
                    // quadratically through a second open cell beyond when there is
                    // one, else linearly.
                    let closure = |i: usize, open: usize, further: Option<usize>| {
                        let taken = (w[i] - free[i]).max(0.0);
                        let near = grow[open].max(0.0);
                        let far = further
                            .filter(|&k| prow[k] <= 0.0)
                            .map(|k| grow[k].max(0.0));
                        if taken + near > 0.0 {
                            gap_closure(-taken, near, far).max(MIN_ENTRY)
                        } else {
                            0.5
                        }
                    };
                    for i in 0..nx - 1 {
                        if prow[i] > 0.0 && prow[i + 1] <= 0.0 {
                            theta[i] = closure(i, i + 1, (i + 2 < nx).then_some(i + 2));
                        }
                        if i > 0 && prow[i] > 0.0 && prow[i - 1] <= 0.0 && prow[i + 1] > 0.0 {
                            exit[i] = closure(i, i - 1, i.checked_sub(2));
                        }
                    }
                },
            );
        Some((entries, exits))
    }

    /// Cells along x.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Rows.
    pub fn ny(&self) -> usize {
        self.ny
    }
}

/// The layer's Jacobian `dw3/dp`: lower triangular in each row in the order of
/// the material path (from largest x) but for one entry per cell, the branches'
/// slope reaching to the downstream neighbour (`J_i,i-1`). `J_ii = diagonal_i`;
/// for j upstream of i it holds the flow's `flow_slope_j` and each branch's
/// `(C_k / C[0]) dF/dp_j (1 - a_k) a_k^(j-i-1) b_k`, plus the slope's terms
/// through the exit values (module docs).
#[derive(Debug, Clone)]
pub struct ViscoelasticJacobian {
    nx: usize,
    /// `dw3_i / dp_i`.
    pub diagonal: Vec<f64>,
    /// `(C_v / C[0]) (h / VT) d(C p)/dp`: the flow's part of every downstream entry.
    pub flow_slope: Vec<f64>,
    /// `dF/dp` of the elastic parts' forcing.
    pub forcing_slope: Vec<f64>,
    /// Per branch (contiguous, for the inner loops): `b`, `a`, `(1 - a) C_k / C[0]`.
    keep_half: Vec<f64>,
    keep_full: Vec<f64>,
    take_full_scaled: Vec<f64>,
    /// The upwind correction's weight: `J_i,i+1` has `- upwind dF/dp_{i+1}`.
    upwind: f64,
    /// Per branch: the exit value's response to `F_upstream - F_downstream`.
    lag_full: Vec<f64>,
    /// The centre value's response to `F_upstream - F_downstream` (all branches):
    /// `J_i,i-1` (the downstream cell) has `- lag_half dF/dp_{i-1}`, the one entry
    /// above the diagonal in the material order.
    lag_half: f64,
    /// `sum_k b_k lag_full_k`: the part of `J_ii` that reaches the centre through
    /// the upstream cell's exit value (included in `diagonal`).
    lag_self: f64,
    /// Fewest rows per rayon task (`usize::MAX`: one thread), from the layer's
    /// passes.
    min_rows: usize,
    /// The layer's entry fractions (empty: none).
    entries: Vec<f64>,
    /// Per cell, whether [`trailing_correction`] is active at the linearisation's
    /// pressure (the line through the centre and the upstream one negative one cell
    /// downstream; empty without branches).
    trailing: Vec<bool>,
    /// The flow's upwind share ([`flow_upwind_share`]).
    flow_upwind: f64,
    /// The rise behind a located leading edge ([`ContactEdge::rise`]).
    rise: Rise,
    /// The branches, for the entry cells.
    branches: Vec<BranchStep>,
    /// Per cell, the index of its entry cell's gains in `entry_gains` (per branch
    /// from there on), `u32::MAX` where it is not an entry cell (empty: no entries).
    entry_slots: Vec<u32>,
    entry_gains: Vec<EntryGains>,
}

/// A branch's gains in an entry cell ([`BranchStep::entry_gains`],
/// [`BranchStep::exit_deficit`]), per unit of `C_k / C[0]`.
#[derive(Debug, Clone, Copy)]
struct EntryGains {
    /// The centre value's, of the cell's forcing and of `d`.
    of_forcing: f64,
    of_slope: f64,
    /// What the rise takes from the exit value, of the same two.
    exit_forcing: f64,
    exit_slope: f64,
}

impl EntryGains {
    fn new(b: &BranchStep, theta: f64, rise: Rise) -> Self {
        let (of_forcing, of_slope) = b.entry_gains(theta, rise);
        let (exit_forcing, exit_slope) = b.exit_deficit(theta, rise);
        EntryGains {
            of_forcing,
            of_slope,
            exit_forcing,
            exit_slope,
        }
    }

    /// What the branch's exit value gains per unit of the downstream neighbour's
    /// forcing, through the centre value and the downstream half cell, less what
    /// the rise takes there.
    fn exit_gain(&self, b: &BranchStep) -> f64 {
        b.keep_half * self.of_slope + 0.5 * b.ramp_half - self.exit_slope
    }
}

impl ViscoelasticJacobian {
    /// `sum_k b_k e_k`: what the branches carry into a cell's centre.
    fn entering(&self, state: &[f64]) -> f64 {
        dot(&self.keep_half, state)
    }

    /// Carries the branch states across a cell whose forcing changed by `df` and
    /// whose neighbours' forcings differ (upstream less downstream) by `rise`.
    fn advance(&self, state: &mut [f64], df: f64, rise: f64) {
        for (((e, a), t), l) in state
            .iter_mut()
            .zip(&self.keep_full)
            .zip(&self.take_full_scaled)
            .zip(&self.lag_full)
        {
            *e = a * *e + t * df + l * rise;
        }
    }

    /// The entry fraction of cell `k` (0: not an entry cell).
    fn entry(&self, k: usize) -> f64 {
        self.entries.get(k).copied().unwrap_or(0.0)
    }

    /// Whether cell `k`'s slope takes the trailing correction.
    fn trailing(&self, k: usize) -> bool {
        self.trailing.get(k).copied().unwrap_or(false)
    }

    /// How many times the slope's downstream term `- lag_half dF_{k-1}` enters
    /// `J_k,k-1`, the entry above the diagonal that the preconditioner leaves out.
    fn above_diagonal_share(&self, k: usize) -> f64 {
        if self.trailing(k) {
            2.0
        } else {
            1.0
        }
    }

    /// The branches' gains of entry cell `k`.
    fn gains(&self, k: usize) -> &[EntryGains] {
        let n = self.branches.len();
        let slot = self.entry_slots[k] as usize;
        &self.entry_gains[slot * n..(slot + 1) * n]
    }

    /// `out = J dp`.
    pub fn apply(&self, dp: &[f64], out: &mut [f64]) {
        let nx = self.nx;
        let rows = dp.par_chunks_exact(nx).zip(out.par_chunks_exact_mut(nx));
        rows.with_min_len(self.min_rows).enumerate().for_each_init(
            || vec![0.0; self.keep_half.len()],
            |state, (r, (drow, orow))| {
                let base = r * nx;
                let diag = &self.diagonal[base..base + nx];
                let slope = &self.flow_slope[base..base + nx];
                let fslope = &self.forcing_slope[base..base + nx];
                let mut upstream = 0.0;
                let mut upstream_forcing = 0.0;
                let mut upstream_flow = 0.0;
                // While nothing has entered the branches, they carry nothing.
                let mut live = false;
                state.fill(0.0);
                let branched = !self.keep_half.is_empty();
                for i in (0..nx).rev() {
                    let df = fslope[i] * drow[i];
                    let next = if i > 0 && branched {
                        fslope[i - 1] * drow[i - 1]
                    } else {
                        0.0
                    };
                    let theta = self.entry(base + i);
                    if theta > 0.0 {
                        // The entry cell (module docs): forced from the edge on.
                        let d = next - df;
                        live = true;
                        let mut carried = 0.0;
                        let mut across = 0.0;
                        let gains = self.gains(base + i);
                        for ((b, e), g) in self.branches.iter().zip(state.iter_mut()).zip(gains) {
                            carried += b.keep_half * *e;
                            across += b.scale * g.of_slope;
                            let centre =
                                b.keep_half * *e + b.scale * (g.of_forcing * df + g.of_slope * d);
                            *e = b.keep_half * centre
                                + b.scale * (b.take_half * df + 0.5 * d * b.ramp_half);
                            *e -= b.scale * (g.exit_forcing * df + g.exit_slope * d);
                        }
                        // `diag` holds the own terms; the downstream neighbour's
                        // through the slope.
                        orow[i] = diag[i] * drow[i] + upstream + carried + across * next;
                        if i > 0 {
                            // The flow's reach to the downstream neighbour.
                            let reach = entry_centre_weights(theta, true, self.rise).1;
                            orow[i] += reach * slope[i - 1] * drow[i - 1];
                        }
                    } else {
                        let before_entry = i > 0 && self.entry(base + i - 1) > 0.0;
                        let trailing = self.trailing(base + i);
                        let downstream = if trailing {
                            2.0 * (next + df) - upstream_forcing
                        } else if before_entry {
                            0.0
                        } else {
                            next
                        };
                        let rise = upstream_forcing - downstream;
                        live |= df != 0.0 || downstream != 0.0;
                        let entering = if live {
                            let e = self.entering(state);
                            self.advance(state, df, rise);
                            e
                        } else {
                            0.0
                        };
                        orow[i] = diag[i] * drow[i] + upstream + entering
                            - self.upwind * upstream_forcing
                            - self.flow_upwind * upstream_flow;
                        if branched {
                            // `diag` holds the upstream exit's share, which
                            // `entering` already carries here; and the downstream
                            // neighbour's term.
                            orow[i] += self.lag_half * rise;
                            if trailing {
                                // `diag` holds the own share of the slope, which
                                // `rise` carries here.
                                orow[i] += 2.0 * self.lag_half * df;
                            }
                            if i + 1 < nx {
                                let up = self.entry(base + i + 1);
                                orow[i] -= if up > 0.0 {
                                    self.entry_share(base + i + 1) * df
                                } else if self.trailing(base + i + 1) {
                                    -2.0 * self.lag_self * df
                                } else {
                                    -self.lag_self * df
                                };
                            }
                        }
                    }
                    upstream_flow = slope[i] * drow[i];
                    upstream += self.flow_passed(base, i) * upstream_flow;
                    upstream_forcing = df;
                }
            },
        );
    }

    /// How much of its own flow cell `i` of the row starting at flat index `base`
    /// passes downstream (module docs): `a` of [`entry_flow_weights`] for an entry
    /// cell, `1 + b` for the cell downstream of one (`b` of its own is already in
    /// its diagonal), 1 elsewhere.
    fn flow_passed(&self, base: usize, i: usize) -> f64 {
        let theta = self.entry(base + i);
        if theta > 0.0 {
            return entry_flow_weights(theta, i > 0, self.rise).0;
        }
        match self.entries.get(base + i + 1) {
            Some(&up) if up > 0.0 && i + 1 < self.nx => {
                1.0 + entry_flow_weights(up, true, self.rise).1
            }
            _ => 1.0,
        }
    }

    /// The part of a cell's `J_ii` that reaches it through the exit value of the
    /// upstream entry cell `k` ([`entry_share`]).
    fn entry_share(&self, k: usize) -> f64 {
        entry_share(&self.branches, self.gains(k))
    }

    /// Solves `(J + extra_diagonal I) y = r` restricted to the cells where `active`
    /// is true (other entries of `y` are set to 0), by forward substitution along
    /// each row from the leading edge. Diagonals that are not safely positive are
    /// replaced by `extra_diagonal` (this is a preconditioner, not an exact solve).
    pub fn solve_restricted(&self, extra_diagonal: f64, active: &[bool], r: &[f64], y: &mut [f64]) {
        let nx = self.nx;
        let rows = y
            .par_chunks_exact_mut(nx)
            .with_min_len(self.min_rows)
            .enumerate();
        rows.for_each_init(
            || vec![0.0; self.keep_half.len()],
            |state, (row, y)| {
                let branched = !self.keep_half.is_empty();
                let base = row * nx;
                let mut upstream = 0.0;
                let mut upstream_forcing = 0.0;
                let mut upstream_flow = 0.0;
                let mut live = false;
                state.fill(0.0);
                for i in (0..nx).rev() {
                    let k = base + i;
                    let entering = if live { self.entering(state) } else { 0.0 };
                    let theta = self.entry(k);
                    if active[k] {
                        let mut d = self.diagonal[k] + extra_diagonal;
                        if d <= 0.1 * extra_diagonal {
                            d = extra_diagonal.max(f64::MIN_POSITIVE);
                        }
                        // The downstream neighbour's share (`- lag_half dF_{i-1}`, above
                        // the diagonal) is left out: a preconditioner.
                        let lag = if branched && theta <= 0.0 {
                            self.lag_half * upstream_forcing * self.above_diagonal_share(k)
                        } else {
                            0.0
                        };
                        let upwind = if theta > 0.0 { 0.0 } else { self.upwind };
                        let flow_upwind = if theta > 0.0 { 0.0 } else { self.flow_upwind };
                        y[i] = (r[k] - upstream - entering
                            + upwind * upstream_forcing
                            + flow_upwind * upstream_flow
                            - lag)
                            / d;
                    } else {
                        y[i] = 0.0;
                    }
                    let df = self.forcing_slope[k] * y[i];
                    live |= df != 0.0;
                    if live && theta > 0.0 {
                        // The entry cell, with its downstream neighbour's forcing
                        // left out.
                        let gains = self.gains(k);
                        for ((b, e), g) in self.branches.iter().zip(state.iter_mut()).zip(gains) {
                            let centre =
                                b.keep_half * *e + b.scale * (g.of_forcing - g.of_slope) * df;
                            let exit = g.exit_forcing - g.exit_slope;
                            *e = b.keep_half * centre
                                + b.scale * (b.take_half - 0.5 * b.ramp_half - exit) * df;
                        }
                    } else if live {
                        if branched && df != 0.0 && i + 1 < nx {
                            // The upstream cell's exit value, now that this cell's
                            // forcing is known (its share of J_ii was in `d`).
                            let up = self.entry(k + 1);
                            if up > 0.0 {
                                let gains = self.gains(k + 1);
                                for ((e, b), g) in state.iter_mut().zip(&self.branches).zip(gains) {
                                    *e += b.scale * g.exit_gain(b) * df;
                                }
                            } else {
                                let share = self.above_diagonal_share(k + 1);
                                for (e, l) in state.iter_mut().zip(&self.lag_full) {
                                    *e -= share * l * df;
                                }
                            }
                        }
                        // The slope's terms but the downstream neighbour's.
                        let rise = if self.trailing(k) {
                            2.0 * (upstream_forcing - df)
                        } else {
                            upstream_forcing
                        };
                        self.advance(state, df, rise);
                    }
                    upstream_flow = self.flow_slope[k] * y[i];
                    upstream += self.flow_passed(base, i) * upstream_flow;
                    upstream_forcing = df;
                }
            },
        );
    }
}

impl LayerResponse for ViscoelasticRows {
    fn displacement(&self, p: &[f64], w3: &mut [f64]) {
        self.row_sweep(p, w3);
    }

    fn linearise(&self, p: &[f64]) -> Box<dyn LayerLinearisation> {
        Box::new(self.jacobian(p))
    }

    fn zero_pressure_self_compliance(&self) -> f64 {
        self.jacobian(&[0.0]).diagonal[0]
    }

    /// `w3 = c p` exactly when the law is linear, nothing flows and every branch
    /// is either frozen (infinite velocity) or relaxed within a cell with no lag
    /// left (a creep length below the smallest double against the cell).
    fn winkler_compliance(&self) -> Option<f64> {
        if self.flow_per_cell != 0.0
            || !matches!(self.layer.law, ComplianceLaw::Linear)
            || self
                .branches
                .iter()
                .any(|b| b.lag_half != 0.0 || b.lag_full != 0.0)
        {
            return None;
        }
        let mut scale = self.glassy_scale;
        for b in &self.branches {
            if b.keep_half == 1.0 && b.keep_full == 1.0 {
                continue;
            }
            if b.keep_half == 0.0 && b.keep_full == 0.0 {
                scale += b.scale;
                continue;
            }
            return None;
        }
        Some(scale * self.reference)
    }

    /// Where a cell's own response `dw3_i/dp_i` is not positive, the discrete row
    /// relation folds (a larger pressure gives a smaller displacement) and the
    /// contact problem has no unique solution. This happens when `C[p] p` decreases
    /// with p (the sigmoid law with delta near 1 at p well above p0) and the cells
    /// are long against the layer's creep lengths `V T`, `V tau_k`.
    fn stall_diagnosis(&self, p: &[f64]) -> Option<String> {
        let jac = self.jacobian(p);
        let worst = (0..p.len())
            .filter(|&k| p[k] > 0.0 && jac.diagonal[k] <= 0.0)
            .map(|k| p[k])
            .fold(f64::INFINITY, f64::min);
        worst.is_finite().then(|| {
            let advice = match &self.layer.law {
                ComplianceLaw::Sigmoid { delta, .. } => format!(
                    "with the sigmoid law C[p] p falls with p somewhere once delta > \
                     {SIGMOID_MONOTONE_DELTA:.3} (here delta = {delta}); use delta <= \
                     {SIGMOID_MONOTONE_DELTA:.3} (C[p] p then rises at every pressure)"
                ),
                ComplianceLaw::Table(_) => "the table's compliance falls faster than 1/p \
                     there, so C[p] p falls: make it fall more slowly (C[p] p rising \
                     with p) above that pressure"
                    .to_string(),
                ComplianceLaw::Linear => "a linear layer should not fold: please report \
                     this case"
                    .to_string(),
            };
            format!(
                "the layer's row relation folds at pressures above about {worst:.3e} (its \
                 displacement falls as the pressure rises, so the discrete problem has no \
                 unique solution, h / (V T) = {:.3e} for the flow); {advice}. Finer cells \
                 move the fold to higher pressures but do not remove it",
                self.flow_per_cell
            )
        })
    }

    /// The relaxed compliance `(C_g + sum C_k) phi(p)` (for the Maxwell layer `C[p]`).
    fn compliance(&self, p: &[f64]) -> Vec<f64> {
        let scale = self
            .branches
            .iter()
            .fold(self.glassy_scale, |s, b| s + b.scale);
        p.par_iter()
            .with_min_len(self.passes.min_cells())
            .map(|&v| scale * self.layer.law.at(self.reference, v).compliance)
            .collect()
    }

    fn dissipated_force(&self, p: &[f64]) -> f64 {
        ViscoelasticRows::dissipated_force(self, p)
    }

    fn relocated(&self, p: &[f64], gap: &[f64]) -> Option<Box<dyn LayerResponse>> {
        let (entries, exits) = self.entries_of(p, gap)?;
        let nx = self.nx;
        let mut edges = Vec::new();
        for (cell, &theta) in entries.iter().enumerate() {
            let i = cell % nx;
            if theta > 0.0 {
                edges.push(ContactEdge {
                    cell,
                    neighbour: (i > 0).then(|| cell - 1),
                    theta,
                    // Set below, once the edge's place is settled.
                    rise: Rise::NONE,
                });
            } else if i > 0
                && i + 1 < nx
                && p[cell] > 0.0
                && p[cell - 1] <= 0.0
                && p[cell + 1] > 0.0
            {
                // A trailing edge: the pressure falls to zero continuously there,
                // where its line through this centre and the upstream one crosses
                // zero (a lagging branch leaves the free gap a kink at the edge);
                // where the branches relax within a few cells, where the free gap
                // closes, as at the leading edge, so that the two ends of a contact
                // are alike (a relaxed layer's friction is the small difference of
                // the two).
                let fall = p[cell + 1] - p[cell];
                let by_pressure = if fall > 0.0 {
                    (p[cell] / fall).min(1.0)
                } else {
                    1.0
                };
                let w = self.trailing_by_pressure;
                let theta = (w * by_pressure + (1.0 - w) * exits[cell]).max(MIN_ENTRY);
                edges.push(ContactEdge {
                    cell,
                    neighbour: Some(cell + 1),
                    theta,
                    rise: Rise::NONE,
                });
            }
        }
        // Each edge's position and the one located from it, for the next secant
        // step (where the two are the same edge: in one row, both leading or both
        // trailing).
        let history: Vec<(f64, f64)> = self
            .edge_list
            .iter()
            .zip(&edges)
            .map(|(a, b)| {
                if same_edge(a, b, nx) {
                    (edge_position(a, nx), edge_position(b, nx))
                } else {
                    (f64::NAN, f64::NAN)
                }
            })
            .collect();
        let (mut edges, settled) = next_edges(&self.edge_list, &self.edge_history, edges, p, nx);
        // The rise behind each leading edge where it now lies.
        for e in edges.iter_mut().filter(|e| e.is_leading()) {
            e.rise = rise_behind(self.rise, e.theta);
        }
        if settled {
            return None;
        }
        let mut entries = vec![0.0; entries.len()];
        for e in edges.iter().filter(|e| e.is_leading()) {
            entries[e.cell] = e.theta;
        }
        let history = if history.len() == edges.len() {
            history
        } else {
            Vec::new()
        };
        Some(Box::new(ViscoelasticRows {
            entries,
            edge_list: edges,
            edge_history: history,
            ..self.clone()
        }))
    }

    fn contact_edges(&self) -> &[ContactEdge] {
        &self.edge_list
    }

    fn places_edges(&self) -> bool {
        self.locates_edges
    }
}

impl LayerLinearisation for ViscoelasticJacobian {
    fn apply(&self, dp: &[f64], out: &mut [f64]) {
        ViscoelasticJacobian::apply(self, dp, out);
    }

    fn solve_restricted(&self, extra_diagonal: f64, active: &[bool], r: &[f64], y: &mut [f64]) {
        ViscoelasticJacobian::solve_restricted(self, extra_diagonal, active, r, y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layer::rheology::{RetardationBranch, Rheology};
    use crate::layer::tests::sigmoid;
    use crate::layer::ComplianceLaw;

    /// A leading edge of row 0 (8 cells) at `position` (in cells, +x upstream).
    fn leading_edge_at(position: f64) -> ContactEdge {
        let cell = (position.ceil() - 1.0) as usize;
        ContactEdge {
            cell,
            neighbour: Some(cell - 1),
            theta: position - cell as f64,
            rise: Rise::NONE,
        }
    }

    /// Runs the relocation's bookkeeping on one leading edge whose solve places it
    /// at `located(position)`, from `start`: the positions solved with, and whether
    /// the edge settled within `MAX_RELOCATIONS` solves.
    fn relocate_one_edge(start: f64, located: impl Fn(f64) -> f64) -> (Vec<f64>, bool) {
        let nx = 8;
        let p = vec![1.0; nx];
        let mut edge = leading_edge_at(start);
        let mut history: Vec<(f64, f64)> = Vec::new();
        let mut solved = vec![start];
        for _ in 0..crate::contact::MAX_RELOCATIONS {
            let here = edge_position(&edge, nx);
            let new = leading_edge_at(located(here));
            let (next, settled) = next_edges(&[edge], &history, vec![new], &p, nx);
            if settled {
                return (solved, true);
            }
            history = vec![(here, edge_position(&new, nx))];
            edge = next[0];
            solved.push(edge_position(&edge, nx));
        }
        (solved, false)
    }

    #[test]
    fn an_edge_located_across_a_centre_moves_there_and_settles() {
        // A place to settle in the next cell: one full step, then it holds still.
        let (solved, settled) = relocate_one_edge(3.9, |_| 4.3);
        assert!(settled, "{solved:?}");
        assert_eq!(solved.len(), 2, "{solved:?}");
        assert!((solved[1] - 4.3).abs() < 1e-12, "{solved:?}");
    }

    #[test]
    fn an_edge_swinging_across_a_centre_settles_on_one_side() {
        // Placed below the centre at 4, it is located 0.15 cell above it, and the
        // other way round (more than CENTRE_CROSSING): no place solves. A full
        // step alternates until the relocations run out; the edge keeps one of
        // the two places and counts as settled once it swings back.
        let (below, above) = (3.94, 4.09);
        let (solved, settled) = relocate_one_edge(below, |x| if x < 4.0 { above } else { below });
        assert!(settled, "{solved:?}");
        assert!(solved.len() <= 3, "{solved:?}");
        let last = *solved.last().unwrap();
        assert!(
            (last - below).abs() < 1e-12 || (last - above).abs() < 1e-12,
            "{solved:?}"
        );
    }

    #[test]
    fn an_edge_nearing_its_cells_centre_settles() {
        // Located a tenth of the way closer to the centre at 4 each time: theta
        // falls towards 0, and a tolerance relative to theta alone is never met.
        // With ENTRY_FLOOR the edge holds still once it moves by 1e-5 cell.
        let (solved, settled) = relocate_one_edge(4.01, |x| 4.0 + 0.9 * (x - 4.0));
        assert!(settled, "{solved:?}");
        let theta = solved.last().unwrap() - 4.0;
        assert!(0.1 * theta <= ENTRY_TOLERANCE * ENTRY_FLOOR, "{solved:?}");
    }

    fn prony(law: ComplianceLaw, integration: Integration, viscosity: Option<f64>) -> Layer {
        Layer {
            rheology: Rheology::Prony {
                glassy_compliance: 0.01,
                branches: vec![
                    RetardationBranch {
                        compliance: 0.02,
                        time: 0.3,
                    },
                    RetardationBranch {
                        compliance: 0.005,
                        time: 4.0,
                    },
                ],
                viscosity,
            },
            law,
            integration,
        }
    }

    #[test]
    fn delta_zero_is_the_linear_law_exactly() {
        for integration in [Integration::Exact, Integration::Secant] {
            let s = ViscoelasticRows::new(sigmoid(0.0, 0.003, integration), 1, 1, 0.1, 1.0);
            let l = ViscoelasticRows::new(
                Layer {
                    law: ComplianceLaw::Linear,
                    ..sigmoid(0.0, 0.003, integration)
                },
                1,
                1,
                0.1,
                1.0,
            );
            for &p in &[0.0, 1e-4, 3e-3, 0.1] {
                assert_eq!(s.forcing(p), l.forcing(p));
                assert_eq!(s.creep(p), l.creep(p));
            }
        }
    }

    #[test]
    fn maxwell_row_sweep_matches_the_explicit_sum_and_correction() {
        // Explicit double loop over eq. 8 (exact integral) and the upwind correction,
        // as in the module docs.
        let op = ViscoelasticRows::new(sigmoid(0.5, 0.002, Integration::Exact), 5, 2, 0.1, 0.01);
        let p: Vec<f64> = (0..10).map(|k| 0.001 * ((k * 7) % 5) as f64).collect();
        let mut w = vec![0.0; 10];
        op.row_sweep(&p, &mut w);
        let k = 0.1 / 0.01;
        // The correction's share at 10 cells of flow per cell of the spring.
        let share = (1.0 / 16.0) * (k - 2.0) / (k + 2.0);
        for r in 0..2 {
            for i in 0..5 {
                let mut s = 0.0;
                for j in i + 1..5 {
                    s += op.creep(p[r * 5 + j]).0;
                }
                let own = op.creep(p[r * 5 + i]).0;
                // The upwind correction of the module docs: its share of the
                // difference from the upstream cell (none beyond the window).
                let upstream = if i + 1 < 5 {
                    op.creep(p[r * 5 + i + 1]).0
                } else {
                    0.0
                };
                let e = op.layer.law_at(p[r * 5 + i]).integral
                    + k * (s + own / 2.0 + share * (own - upstream));
                assert!((w[r * 5 + i] - e).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn kelvin_voigt_branch_matches_the_ode_solution() {
        // A linear Kelvin–Voigt branch, tau w' + w = C p(t), integrated in fine
        // steps along the path through the centred reconstruction of the pressure
        // (linear in each cell, module docs), read at each cell centre.
        let (c, tau, v, h) = (0.03, 0.7, 0.4, 0.1);
        for v in [v, 0.02, 4.0] {
            let nx = 7;
            let op = ViscoelasticRows::new(linear_kelvin_voigt(c, tau), nx, 1, h, v);
            let p: Vec<f64> = (0..nx).map(|k| 0.001 * (1 + (k * 3) % 5) as f64).collect();
            let mut w = vec![0.0; nx];
            op.row_sweep(&p, &mut w);
            // The slope's share (module docs), 1 - exp(-(10 h / (V tau))^2).
            let x = h / (v * tau);
            let weight = 1.0 - (-100.0 * x * x).exp();
            let centres = integrate_branch(
                &p,
                c,
                tau,
                h / v,
                |p, j, s| reconstructed(p, j, s, weight),
                |_, _, _| {},
            );
            let scale = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for i in 0..nx {
                // The damping correction (module docs: kappa = 0.1, share 1 without a
                // glassy spring, faded by e^(-2x)), with the upstream cell's forcing.
                let x = h / (v * tau);
                let upstream = if i + 1 < nx { c * p[i + 1] } else { 0.0 };
                let e = centres[i]
                    + 0.1
                        * ((-x / 2.0).exp() - (-x).exp())
                        * (-2.0 * x).exp()
                        * (c * p[i] - upstream);
                assert!(
                    (w[i] - e).abs() < 1e-9 * scale,
                    "V {v}, cell {i}: {} {e}",
                    w[i]
                );
            }
        }
    }

    /// A Kelvin–Voigt layer of compliance `c` and retardation time `tau`, linear law.
    fn linear_kelvin_voigt(c: f64, tau: f64) -> Layer {
        Layer {
            rheology: Rheology::KelvinVoigt {
                compliance: c,
                retardation_time: tau,
            },
            law: ComplianceLaw::Linear,
            integration: Integration::Exact,
        }
    }

    /// The pressure at the fraction `s` of the way through cell `j` along the
    /// material path (0 at its upstream face), continuous and linear between cell
    /// centres (the dissipated power's profile, module docs).
    fn hat(p: &[f64], j: usize, s: f64) -> f64 {
        let up = p.get(j + 1).copied().unwrap_or(0.0);
        let down = if j > 0 { p[j - 1] } else { 0.0 };
        if s < 0.5 {
            p[j] + (up - p[j]) * (0.5 - s)
        } else {
            p[j] + (down - p[j]) * (s - 0.5)
        }
    }

    /// The same for the centred linear reconstruction of the layer's response.
    fn reconstructed(p: &[f64], j: usize, s: f64, weight: f64) -> f64 {
        let up = p.get(j + 1).copied().unwrap_or(0.0);
        let down = if j > 0 { p[j - 1] } else { 0.0 };
        p[j] + weight * 0.5 * (up - down) * (0.5 - s)
    }

    /// A linear Kelvin–Voigt branch `tau w' + w = C p` integrated along a row in
    /// 20000 exact exponential steps per cell (each at its midpoint's pressure),
    /// then 40 cells of free relaxation; `dashpot(w_before, w_after, dt)` sees each
    /// step. Returns w at every cell centre.
    fn integrate_branch(
        p: &[f64],
        c: f64,
        tau: f64,
        dt_cell: f64,
        profile: impl Fn(&[f64], usize, f64) -> f64,
        mut dashpot: impl FnMut(f64, f64, f64),
    ) -> Vec<f64> {
        let steps = 20000;
        let dt = dt_cell / steps as f64;
        let mut w: f64 = 0.0;
        let mut centres = vec![0.0; p.len()];
        for j in (0..p.len())
            .rev()
            .chain(std::iter::repeat_n(usize::MAX, 40))
        {
            for k in 0..steps {
                let pj = if j == usize::MAX {
                    0.0
                } else {
                    profile(p, j, (k as f64 + 0.5) / steps as f64)
                };
                let target = c * pj;
                let w_new = target + (w - target) * (-dt / tau).exp();
                dashpot(w, w_new, dt);
                w = w_new;
                if j != usize::MAX && k + 1 == steps / 2 {
                    centres[j] = w;
                }
            }
        }
        centres
    }

    /// `J dp` against central differences of the row sweep at `p` along `dp`.
    fn assert_jacobian_is_the_derivative(
        op: &ViscoelasticRows,
        jac: &ViscoelasticJacobian,
        p: &[f64],
        dp: &[f64],
    ) {
        let n = p.len();
        let mut jd = vec![0.0; n];
        jac.apply(dp, &mut jd);
        let e = 1e-8;
        let plus: Vec<f64> = p.iter().zip(dp).map(|(a, b)| a + e * b).collect();
        let minus: Vec<f64> = p.iter().zip(dp).map(|(a, b)| a - e * b).collect();
        let (mut wp, mut wm) = (vec![0.0; n], vec![0.0; n]);
        op.row_sweep(&plus, &mut wp);
        op.row_sweep(&minus, &mut wm);
        for k in 0..n {
            let fd = (wp[k] - wm[k]) / (2.0 * e);
            assert!(
                (jd[k] - fd).abs() < 1e-6 * fd.abs().max(1e-3),
                "{k}: {} {fd}",
                jd[k]
            );
        }
    }

    /// The two-branch Prony layer with a flow under a sigmoid law.
    fn sigmoid_prony_with_flow() -> Layer {
        prony(
            ComplianceLaw::Sigmoid {
                delta: 0.6,
                p0: 0.002,
            },
            Integration::Exact,
            Some(30.0),
        )
    }

    /// `J y` less the entries above the diagonal (the downstream neighbour's share
    /// of a branch's slope), which the preconditioner leaves out; rows of `nx`.
    fn lower_product(jac: &ViscoelasticJacobian, nx: usize, y: &[f64], out: &mut [f64]) {
        jac.apply(y, out);
        for k in (0..y.len()).filter(|k| k % nx > 0) {
            out[k] +=
                jac.above_diagonal_share(k) * jac.lag_half * jac.forcing_slope[k - 1] * y[k - 1];
        }
    }

    #[test]
    fn jacobian_matches_finite_differences_and_inverts() {
        let layers = [
            sigmoid(0.8, 0.002, Integration::Exact),
            sigmoid(0.8, 0.002, Integration::Secant),
            sigmoid_prony_with_flow(),
            prony(
                ComplianceLaw::Sigmoid {
                    delta: 0.6,
                    p0: 0.002,
                },
                Integration::Secant,
                None,
            ),
        ];
        for layer in layers {
            let op = ViscoelasticRows::new(layer, 6, 2, 0.1, 0.03);
            let p: Vec<f64> = (0..12).map(|k| 0.0007 * (1 + (k * 5) % 7) as f64).collect();
            let jac = op.jacobian(&p);
            let dp: Vec<f64> = (0..12).map(|k| ((k * 3) % 4) as f64 - 1.5).collect();
            assert_jacobian_is_the_derivative(&op, &jac, &p, &dp);
            let lower = |y: &[f64], out: &mut [f64]| lower_product(&jac, 6, y, out);
            // The restricted triangular solve inverts that on all-active cells ...
            let active = vec![true; 12];
            let mut y = vec![0.0; 12];
            let mut lower_dp = vec![0.0; 12];
            lower(&dp, &mut lower_dp);
            jac.solve_restricted(0.0, &active, &lower_dp, &mut y);
            for k in 0..12 {
                assert!((y[k] - dp[k]).abs() < 1e-9, "{k}");
            }
            // ... and on a subset it inverts the principal submatrix: J restricted to
            // the active cells applied to y gives back r there.
            let active: Vec<bool> = (0..12).map(|k| k % 3 != 1).collect();
            let r: Vec<f64> = (0..12).map(|k| 1e-3 * (k as f64 - 5.0)).collect();
            jac.solve_restricted(0.0, &active, &r, &mut y);
            let mut jy = vec![0.0; 12];
            lower(&y, &mut jy);
            for k in (0..12).filter(|&k| active[k]) {
                assert!((jy[k] - r[k]).abs() < 1e-12, "{k}: {} {}", jy[k], r[k]);
            }
        }
    }

    #[test]
    fn a_trailing_edge_cell_takes_the_one_sided_slope() {
        // A Kelvin–Voigt branch relaxing within a hundredth of a cell: its centre
        // value is `F_i + L dF/dx` to within e^(-50), with the slope `(F_{i+1} -
        // F_{i-1}) / 2h` inside the contact and `(F_{i+1} - F_i) / h` in the last
        // loaded cell before the trailing edge (its downstream neighbour unloaded).
        let (c, tau, h) = (0.02, 1.0, 0.1);
        let v = h / (100.0 * tau);
        let nx = 8;
        let op = ViscoelasticRows::new(linear_kelvin_voigt(c, tau), nx, 1, h, v);
        let p = [0.0, 0.0, 0.3, 1.0, 1.6, 2.0, 1.5, 0.9].map(|x| 1e-3 * x);
        let mut w = vec![0.0; nx];
        op.row_sweep(&p, &mut w);
        let lag = v * tau / h;
        let trailing = c * (p[2] + lag * (p[3] - p[2]));
        assert!(
            (w[2] - trailing).abs() < 1e-13 * trailing,
            "{} {trailing}",
            w[2]
        );
        let centred = c * (p[3] + lag * (p[4] - p[2]) / 2.0);
        assert!(
            (w[3] - centred).abs() < 1e-13 * centred,
            "{} {centred}",
            w[3]
        );
    }

    #[test]
    fn jacobian_with_trailing_edge_cells_matches_finite_differences_and_inverts() {
        // Two cells with the trailing correction (the forcing rising by more than
        // the sum of the two values below), every pressure positive so that the
        // finite differences stay on one side of each kink.
        let nx = 8;
        for layer in [
            linear_kelvin_voigt(0.02, 1.0),
            prony(ComplianceLaw::Linear, Integration::Exact, None),
            sigmoid_prony_with_flow(),
        ] {
            let op = ViscoelasticRows::new(layer, nx, 1, 0.1, 0.05);
            let p = [0.01, 0.05, 0.3, 1.0, 1.6, 2.0, 1.5, 0.9].map(|x| 1e-3 * x);
            let jac = op.jacobian(&p);
            assert_eq!(
                (0..nx).filter(|&k| jac.trailing(k)).collect::<Vec<_>>(),
                vec![1, 2]
            );
            let dp: Vec<f64> = (0..nx).map(|k| ((k * 3) % 4) as f64 - 1.5).collect();
            assert_jacobian_is_the_derivative(&op, &jac, &p, &dp);
            // The preconditioner inverts J less its entries above the diagonal.
            let mut y = vec![0.0; nx];
            let mut lower_dp = vec![0.0; nx];
            lower_product(&jac, nx, &dp, &mut lower_dp);
            jac.solve_restricted(0.0, &[true; 8], &lower_dp, &mut y);
            for k in 0..nx {
                assert!((y[k] - dp[k]).abs() < 1e-9, "{k}: {} {}", y[k], dp[k]);
            }
        }
    }

    /// `op` with entries at the cells and thetas given (the relocation's result).
    fn with_entries(op: &ViscoelasticRows, at: &[(usize, f64)]) -> ViscoelasticRows {
        let mut entries = vec![0.0; op.nx * op.ny];
        for &(cell, theta) in at {
            entries[cell] = theta;
        }
        ViscoelasticRows {
            entries,
            ..op.clone()
        }
    }

    #[test]
    fn jacobian_with_located_entries_matches_finite_differences_and_inverts() {
        // Entry cells (their upstream neighbour unloaded) in both rows, one at the
        // row's downstream end; Burgers-like (glassy, branches, flow) and
        // Kelvin–Voigt-like (branches only) layers, nonlinear laws.
        let kelvin_voigt = Layer {
            rheology: Rheology::Prony {
                glassy_compliance: 0.0,
                branches: vec![
                    RetardationBranch {
                        compliance: 0.02,
                        time: 1.0,
                    },
                    RetardationBranch {
                        compliance: 0.01,
                        time: 0.1,
                    },
                ],
                viscosity: None,
            },
            law: ComplianceLaw::Sigmoid {
                delta: 0.6,
                p0: 0.002,
            },
            integration: Integration::Exact,
        };
        let layers = [
            sigmoid_prony_with_flow(),
            prony(ComplianceLaw::Linear, Integration::Secant, None),
            kelvin_voigt,
        ];
        // And the paper's Maxwell layer with h / (V T) = 6.7: its pressure rises over
        // 0.15 cells behind the edges (shortened at theta = 0.01).
        let maxwell = Layer::maxwell(
            0.02,
            0.5,
            ComplianceLaw::Sigmoid {
                delta: 0.6,
                p0: 0.002,
            },
            Integration::Exact,
        );
        // And a Burgers layer whose pressure rises over two exponentials.
        let burgers = Layer {
            rheology: Rheology::Burgers {
                glassy_compliance: 0.02,
                relaxation_time: 0.5,
                compliance: 0.02,
                retardation_time: 0.2,
            },
            law: ComplianceLaw::Sigmoid {
                delta: 0.6,
                p0: 0.002,
            },
            integration: Integration::Exact,
        };
        assert_eq!(
            ViscoelasticRows::new(burgers.clone(), 6, 2, 0.1, 0.03)
                .rise
                .terms()
                .count(),
            2
        );
        let entries = [(3, 0.3), (6, 0.8), (9, 0.05)];
        let cases = layers.into_iter().map(|l| (l, entries)).chain([
            (maxwell.clone(), entries),
            (maxwell, [(3, 0.01), (6, 0.5), (9, 0.2)]),
            (burgers.clone(), entries),
            (burgers, [(3, 0.01), (6, 0.5), (9, 0.2)]),
        ]);
        for (layer, entries) in cases {
            let base = ViscoelasticRows::new(layer, 6, 2, 0.1, 0.03);
            let op = with_entries(&base, &entries);
            let mut p: Vec<f64> = (0..12).map(|k| 0.0007 * (1 + (k * 5) % 7) as f64).collect();
            // Nearly unloaded upstream of the entries (at zero the laws' second
            // derivative jumps, which a central difference does not like).
            for k in [4, 10] {
                p[k] = 1e-6;
            }
            let jac = op.jacobian(&p);
            let dp: Vec<f64> = (0..12).map(|k| ((k * 3) % 4) as f64 - 1.5).collect();
            assert_jacobian_is_the_derivative(&op, &jac, &p, &dp);
            // The entries above the diagonal, by finite differences of unit
            // perturbations, are what the preconditioner leaves out.
            let above = |k: usize| {
                let mut unit = vec![0.0; 12];
                unit[k - 1] = 1.0;
                let mut out = vec![0.0; 12];
                jac.apply(&unit, &mut out);
                out[k]
            };
            let upper: Vec<f64> = (0..12)
                .map(|k| if k % 6 > 0 { above(k) } else { 0.0 })
                .collect();
            let lower = |y: &[f64], out: &mut [f64]| {
                jac.apply(y, out);
                for k in 0..12 {
                    if k % 6 > 0 {
                        out[k] -= upper[k] * y[k - 1];
                    }
                }
            };
            let active = vec![true; 12];
            let mut y = vec![0.0; 12];
            let mut lower_dp = vec![0.0; 12];
            lower(&dp, &mut lower_dp);
            jac.solve_restricted(0.0, &active, &lower_dp, &mut y);
            for k in 0..12 {
                assert!((y[k] - dp[k]).abs() < 1e-9, "{k}: {} {}", y[k], dp[k]);
            }
        }
    }

    #[test]
    fn the_entry_flow_integrates_the_rising_creep_rate() {
        // The flow at an entry cell's centre: the creep rate from the edge to the
        // centre, linear through the two centres times 1 - e^(-s / rise), by
        // quadrature; and the moments the dissipation uses.
        use crate::layer::tests::simpson;
        let (q, next) = (0.4, 0.9);
        for theta in [2e-3, 0.05, 0.3, 1.0] {
            for rise in [0.0, 0.01, 0.2, 0.9] {
                let (a, b) = entry_centre_weights(theta, true, Rise::single(rise));
                let rise = rise.min(10.0 * theta);
                let rate = |s: f64| {
                    let line = q + (s - theta) * (next - q);
                    if rise > 0.0 {
                        line * (1.0 - (-s / rise).exp())
                    } else {
                        line
                    }
                };
                let quadrature = simpson(rate, 0.0, theta, 40_000);
                let centre = a * q + b * next;
                assert!(
                    (centre - quadrature).abs() < 1e-10,
                    "theta {theta}, rise {rise}: {centre} {quadrature}"
                );
            }
        }
        for (x, l) in [(0.7, 0.05), (0.3, 0.9), (1.5, 1e-3)] {
            let m = exponential_moments(x, l);
            for (n, &mn) in m.iter().enumerate() {
                let f = |s: f64| s.powi(n as i32) * (-s / l).exp();
                let quadrature = simpson(f, 0.0, x, 40_000);
                assert!(
                    (mn - quadrature).abs() < 1e-10 * (1.0 + quadrature),
                    "{n}: {mn} {quadrature}"
                );
            }
        }
        // The rise is shortened only for an edge within a tenth of it from the centre.
        assert_eq!(rise_behind(Rise::single(0.2), 0.05).lengths[0], 0.2);
        assert!((rise_behind(Rise::single(0.2), 0.01).lengths[0] - 0.1).abs() < 1e-15);
    }

    #[test]
    fn an_entry_cell_behind_a_rise_dissipates_its_flows_work() {
        // The paper's Maxwell layer (linear law) with h / (V T) = 5: the flow places
        // edges and the pressure rises over C_g / flow per cell = 0.2 cells. One row
        // of six cells entered at theta = 0.3 in cell 3: the flow dissipates `p dw_v`
        // with `dw_v / ds = (h / V T) q` per cell, q = C p; over the entry cell both
        // p and q are their line through the two centres times 1 - e^(-s / rise),
        // elsewhere the centre values (by quadrature here).
        use crate::layer::tests::simpson;
        let (c, t, v, h) = (0.02, 1.0, 0.02, 0.1);
        let layer = Layer::maxwell(c, t, ComplianceLaw::Linear, Integration::Exact);
        let base = ViscoelasticRows::new(layer, 6, 1, h, v);
        assert_eq!(base.rise.terms().count(), 1);
        assert!(
            (base.rise.lengths[0] - 0.2).abs() < 1e-12,
            "{:?}",
            base.rise
        );
        let theta = 0.3;
        let op = with_entries(&base, &[(3, theta)]);
        let p = [0.002, 0.003, 0.0025, 0.001, 0.0, 0.0];
        let flow_per_cell = h / (v * t);
        // The creep rate `C p` (per unit of the flow's `C / C[0]` = 1 here).
        let rate = |pressure: f64| c * pressure;
        let mut expected = 0.0;
        for &pi in &p[..3] {
            expected += flow_per_cell * pi * rate(pi);
        }
        let line = |s: f64| p[3] + (s - theta) * (p[2] - p[3]);
        let profile = |s: f64| line(s) * (1.0 - (-s / 0.2).exp());
        expected +=
            flow_per_cell * simpson(|s| profile(s) * rate(profile(s)), 0.0, theta + 0.5, 20_000);
        // Per unit length of the path, on a row h wide.
        let d = op.dissipated_force(&p) / h;
        assert!((d - expected).abs() < 1e-10 * expected, "{d} {expected}");
    }

    /// A branch of unit scale relaxing over `1 / x` cells (x may be infinite).
    fn unit_branch(x: f64) -> BranchStep {
        BranchStep {
            scale: 1.0,
            keep_full: (-x).exp(),
            take_full: -(-x).exp_m1(),
            keep_half: (-0.5 * x).exp(),
            take_half: -(-0.5 * x).exp_m1(),
            lag_half: 0.0,
            lag_full: 0.0,
            ramp_half: ramp_gain(0.5 * x),
            cells_per_creep_length: x,
        }
    }

    /// The branch `w' = x (F - w)` (cells) from `w(0) = start` under the forcing
    /// `forcing(s)` to `s = end`, by RK4 on `n` steps, with `visit(s, w, w')` at
    /// every step's start and the end; for infinite x the branch is the forcing and
    /// its slope by a central difference.
    fn brute_branch(
        x: f64,
        start: f64,
        forcing: impl Fn(f64) -> f64,
        end: f64,
        n: usize,
        mut visit: impl FnMut(f64, f64, f64),
    ) -> f64 {
        let ds = end / n as f64;
        if x.is_infinite() {
            for k in 0..=n {
                let s = k as f64 * ds;
                let e = 1e-7 * end;
                let slope =
                    (forcing(s + e) - forcing((s - e).max(0.0))) / (s + e - (s - e).max(0.0));
                visit(s, forcing(s), slope);
            }
            return forcing(end);
        }
        let rate = |s: f64, w: f64| x * (forcing(s) - w);
        let mut w = start;
        for k in 0..n {
            let s = k as f64 * ds;
            visit(s, w, rate(s, w));
            let k1 = rate(s, w);
            let k2 = rate(s + 0.5 * ds, w + 0.5 * ds * k1);
            let k3 = rate(s + 0.5 * ds, w + 0.5 * ds * k2);
            let k4 = rate(s + ds, w + ds * k3);
            w += ds / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        }
        visit(end, w, rate(end, w));
        w
    }

    #[test]
    fn a_branch_behind_a_rise_follows_its_equation() {
        // From an edge theta cells upstream of the centre, forced by the line
        // `f + d (s - theta)` times 1 - e^(-s / rise): the centre value's gains and
        // the value anywhere behind the edge against RK4 on the branch's equation,
        // for creep lengths from 3 cells to a fortieth and a branch relaxed at once.
        let (f, d) = (0.8, -0.3);
        let rises: [&[(f64, f64)]; 5] = [
            &[],
            &[(1.0, 0.01)],
            &[(1.0, 0.2)],
            &[(1.0, 0.9)],
            &[(0.6, 0.03), (0.3, 0.4), (0.1, 2.0)],
        ];
        for x in [0.3, 3.0, 40.0, f64::INFINITY] {
            for theta in [0.05, 0.5, 1.0] {
                for terms in rises {
                    let b = unit_branch(x);
                    let mut rise = Rise::NONE;
                    for (m, &(a, l)) in terms.iter().enumerate() {
                        rise.amplitudes[m] = a;
                        rise.lengths[m] = l;
                    }
                    // Each length at most ten times theta (`rise_behind`).
                    let rho = |s: f64| {
                        1.0 - terms
                            .iter()
                            .map(|&(a, l)| a * (-s / l.min(10.0 * theta)).exp())
                            .sum::<f64>()
                    };
                    let forcing = |s: f64| (f + d * (s - theta)) * rho(s);
                    let n = 200_000;
                    let expected = brute_branch(x, 0.0, forcing, theta, n, |_, _, _| {});
                    let (of_f, of_d) = b.entry_gains(theta, rise);
                    let centre = of_f * f + of_d * d;
                    assert!(
                        (centre - expected).abs() < 1e-9,
                        "x {x}, theta {theta}, rise {terms:?}: {centre} {expected}"
                    );
                    if !terms.is_empty() {
                        let start = 0.25;
                        let l = rise_behind(rise, theta);
                        for s in [0.3 * theta, theta, theta + 0.5] {
                            let expected = brute_branch(x, start, forcing, s, n, |_, _, _| {});
                            let value = b.behind_rise(start, (f - d * theta, d), s, l);
                            assert!(
                                (value - expected).abs() < 1e-9,
                                "x {x}, theta {theta}, rise {terms:?}, s {s}: {value} {expected}"
                            );
                        }
                    }
                }
            }
        }
        // The moments against quadrature, across the series' switch.
        for (t, rate) in [(0.7, 0.0), (0.7, 0.7), (0.7, 0.72), (2.0, 30.0)] {
            let m = decaying_moments(t, rate);
            for (n, &mn) in m.iter().enumerate() {
                let q = crate::layer::tests::simpson(
                    |s| s.powi(n as i32) * (-rate * s).exp(),
                    0.0,
                    t,
                    20_000,
                );
                assert!((mn - q).abs() < 1e-13, "{t} {rate} {n}: {mn} {q}");
            }
        }
    }

    #[test]
    fn a_rise_with_branches_solves_the_layer_behind_a_flat_edge() {
        // The rise's terms (roots and residues of the Laplace transform) against
        // the layer's equation behind an edge whose interference grows linearly,
        // `C_g p + sum_k w_k + F int_0^s p = F A s`, the branches integrated by RK4
        // from zero and the flow by the trapezoidal rule on a grid fine against
        // every length; and the two sums the module docs state.
        let branch = |c: f64, t: f64| RetardationBranch {
            compliance: c,
            time: t,
        };
        let layers = [
            // Burgers (glassy 1, one branch, flow; per unit of C[0]).
            (0.02, vec![branch(0.02, 0.3)], 0.02),
            // No glassy spring: the pressure jumps at the edge, then rises.
            (0.0, vec![branch(0.02, 0.1), branch(0.01, 1.0)], 0.02),
            // Six branches: merged into four terms.
            (
                0.01,
                (0..6).map(|k| branch(0.005, 0.01 * 4f64.powi(k))).collect(),
                0.02,
            ),
        ];
        let (h, v, t) = (0.1, 0.01, 1.0);
        for (glassy, branches, viscosity_compliance) in layers {
            let layer = Layer {
                rheology: Rheology::Prony {
                    glassy_compliance: glassy,
                    branches: branches.clone(),
                    viscosity: Some(t / viscosity_compliance),
                },
                law: ComplianceLaw::Linear,
                integration: Integration::Exact,
            };
            let rows = ViscoelasticRows::new(layer, 4, 1, h, v);
            let reference = rows.reference;
            let flow = viscosity_compliance / reference * h / (v * t);
            let rise = rows.rise;
            let springs = (glassy + branches.iter().map(|b| b.compliance).sum::<f64>()) / reference;
            let (sum_a, sum_al): (f64, f64) = rise
                .terms()
                .fold((0.0, 0.0), |(s, sl), (a, l)| (s + a, sl + a * l));
            assert!((sum_al - springs / flow).abs() < 1e-12 * sum_al, "{sum_al}");
            if glassy > 0.0 && branches.len() < 4 {
                assert!((sum_a - 1.0).abs() < 1e-12, "{sum_a}");
            }
            if branches.len() > 4 {
                // Merged: the sums hold, the shape only nearly.
                assert_eq!(rise.terms().count(), RISE_TERMS);
                continue;
            }
            assert!(sum_a <= 1.0 + 1e-12);
            let p = |s: f64| rise.share(s);
            // Along s in cells, A = 1: w_k' = x_k (C_k p - w_k).
            let shortest = rise.terms().map(|t| t.1).fold(f64::INFINITY, f64::min);
            let end = 3.0 * rise.terms().map(|t| t.1).fold(0.0, f64::max);
            let n = ((end / shortest) * 2000.0) as usize;
            let ds = end / n as f64;
            let mut worst: f64 = 0.0;
            let mut states = vec![0.0; branches.len()];
            let mut flowed = 0.0;
            for k in 0..n {
                let s = k as f64 * ds;
                for (w, b) in states.iter_mut().zip(&branches) {
                    let x = h / (v * b.time);
                    let c = b.compliance / reference;
                    let rate = |u: f64, w: f64| x * (c * p(u) - w);
                    let k1 = rate(s, *w);
                    let k2 = rate(s + 0.5 * ds, *w + 0.5 * ds * k1);
                    let k3 = rate(s + 0.5 * ds, *w + 0.5 * ds * k2);
                    let k4 = rate(s + ds, *w + ds * k3);
                    *w += ds / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
                }
                flowed += 0.5 * ds * (p(s) + p(s + ds));
                let at = s + ds;
                let w: f64 = states.iter().sum();
                let residual = glassy / reference * p(at) + w + flow * flowed - flow * at;
                worst = worst.max(residual.abs() / (flow * at));
            }
            assert!(worst < 1e-6, "{glassy} {:?}: {worst:e}", rise);
        }
    }

    #[test]
    fn a_branch_behind_a_rise_does_the_work_of_its_path() {
        // `int p dw` from the edge to the centre, pressure and forcing their lines
        // times 1 - e^(-s / l), the branch entering at 0.25: against RK4 for w and
        // Simpson's rule for `int p w' ds` on a grid fine against l and the creep
        // length.
        let (pressure, forcing) = ((0.002, 0.001), (0.5, 0.2));
        let rule = GaussLegendre::new(8);
        let two = Rise {
            amplitudes: [0.7, 0.3, 0.0, 0.0],
            lengths: [0.02, 0.6, 0.0, 0.0],
        };
        for x in [0.3, 3.0, 40.0, f64::INFINITY] {
            let cases = [
                (0.5, Rise::single(0.01)),
                (1.0, Rise::single(0.2)),
                (0.05, Rise::single(0.3)),
                (1.2, two),
            ];
            for (theta, l) in cases {
                let b = unit_branch(x);
                let rise = |s: f64| {
                    1.0 - l
                        .amplitudes
                        .iter()
                        .zip(&l.lengths)
                        .filter(|t| *t.0 > 0.0)
                        .map(|(a, k)| a * (-s / k).exp())
                        .sum::<f64>()
                };
                let p = |s: f64| (pressure.0 + pressure.1 * s) * rise(s);
                let force = |s: f64| (forcing.0 + forcing.1 * s) * rise(s);
                let n = 400_000;
                let mut samples = Vec::with_capacity(n + 1);
                let end = brute_branch(x, 0.25, force, theta, n, |s, _, slope| {
                    samples.push(p(s) * slope)
                });
                let ds = theta / n as f64;
                let expected = ds / 3.0
                    * samples
                        .iter()
                        .enumerate()
                        .map(|(k, v)| {
                            v * if k == 0 || k == n {
                                1.0
                            } else if k % 2 == 1 {
                                4.0
                            } else {
                                2.0
                            }
                        })
                        .sum::<f64>();
                let mut e = 0.25;
                let path = RisingPath::new(pressure, theta, l, shortest_scale(l, &[b]), &rule);
                let work = b.rising_segment_work(&mut e, &path, forcing);
                assert!(
                    (work - expected).abs() < 1e-7 * expected.abs(),
                    "x {x}, theta {theta}, l {l:?}: {work} {expected}"
                );
                assert!((e - end).abs() < 1e-9, "{e} {end}");
            }
        }
    }

    #[test]
    fn dissipation_of_a_linear_branch_is_its_dashpot_work() {
        // For the linear law the branch dissipates (tau / C) (dw/dt)^2; integrate it
        // over time along a row by fine quadrature of the exact solution (the
        // pressure continuous and linear between the window's cell centres, then
        // the free relaxation behind it), at a creep length of 1.7 cells and of a
        // fiftieth of a cell.
        let (c, tau, v, h) = (0.02, 0.5, 0.3, 0.1);
        let layer = linear_kelvin_voigt(c, tau);
        let p = [0.0, 0.002, 0.004, 0.003, 0.001, 0.0];
        for v in [v, 0.004] {
            let op = ViscoelasticRows::new(layer.clone(), p.len(), 1, h, v);
            let d = op.dissipated_force(&p) / h;
            // Energy per unit area: integral of (tau / C) w'^2 dt, w' = (C p - w) /
            // tau, the rate of each step from its exact end values.
            let mut energy = 0.0;
            integrate_branch(&p, c, tau, h / v, hat, |w, w_new, dt| {
                let rate = (w_new - w) / dt;
                energy += tau / c * rate * rate * dt;
            });
            assert!((d - energy).abs() < 1e-6 * energy, "V {v}: {d} {energy}");
        }
    }
}
