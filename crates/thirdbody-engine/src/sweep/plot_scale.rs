//! The mu axis of a sweep's plot, `[sweep] plot_scale` (docs/sweeps.md): a
//! setting of the sweep file, kept in `sweep.json`, that the front ends' plots read.

use serde::{Deserialize, Serialize};

/// The mu axis of the plot: `[sweep] plot_scale` (docs/sweeps.md).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PlotScale {
    /// Logarithmic when every plotted mu is > 0 and they span more than
    /// [`AUTO_LOG_SPAN`], linear otherwise.
    #[default]
    Auto,
    /// Always linear.
    Linear,
    /// Logarithmic (linear after all when some plotted mu is <= 0).
    Log,
}

/// Ratio of the largest to the smallest plotted mu above which the automatic scale is
/// logarithmic: one and a half decades.
pub const AUTO_LOG_SPAN: f64 = 30.0;

impl PlotScale {
    /// The values `[sweep] plot_scale` accepts.
    pub const NAMES: [&'static str; 3] = ["auto", "linear", "log"];

    /// The scale called `name`.
    pub fn from_name(name: &str) -> Option<PlotScale> {
        match name {
            "auto" => Some(PlotScale::Auto),
            "linear" => Some(PlotScale::Linear),
            "log" => Some(PlotScale::Log),
            _ => None,
        }
    }

    /// Whether this is the default (left out of `sweep.json`).
    pub fn is_auto(&self) -> bool {
        *self == PlotScale::Auto
    }

    /// Whether the mu axis of plotted values `mu` is logarithmic.
    pub fn log_axis(self, mu: &[f64]) -> bool {
        let (lo, hi) = mu
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let positive = !mu.is_empty() && lo > 0.0;
        match self {
            PlotScale::Linear => false,
            PlotScale::Log => positive,
            PlotScale::Auto => positive && hi / lo > AUTO_LOG_SPAN,
        }
    }
}
