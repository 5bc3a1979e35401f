//! The cases of a sweep: the Cartesian product of its axes in row-major order (the
//! first axis varies slowest, the last fastest), each case's full case-file text (the
//! base case with the case's values set), and its stable id `NNNN-hhhhhhhh`: the index
//! in the product and a 32-bit FNV-1a hash of the values it sets, so that a record is
//! never mistaken for another case's.
//!
//! Every case goes through the library's normal [`parse_case_file`], so each value is
//! checked exactly as in a single case file (unknown keys, unused keys, ranges).
//! [`Sweep::new`] checks all cases before anything runs; height maps are read once
//! per file and cell size.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use thirdbody::case_file::{parse_case_file, CaseFile};
use thirdbody::HeightMap;

use super::plot_scale::PlotScale;
use super::spec::{apply, read_spec, Axis, Spec, VARIANT_AXIS};
use super::values::KeyValue;
use super::SweepError;

/// A sweep ready to run: the base case, the axes and the product.
#[derive(Debug)]
pub struct Sweep {
    spec: Spec,
    base_dir: PathBuf,
    ids: Vec<String>,
    maps: MapCache,
    /// Each case's estimated peak memory (solve and stresses), from [`Sweep::check_cases`].
    case_bytes: Vec<f64>,
}

impl Sweep {
    /// Reads a case file with an optional `[sweep]` section plus `--vary` arguments and
    /// checks every case; height maps are read relative to the file's folder.
    pub fn from_file(path: &Path, vary: &[String]) -> Result<Sweep, SweepError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            SweepError::spec(format!("cannot read the case file {}: {e}", path.display()))
        })?;
        let base_dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        Sweep::new(&text, &base_dir, vary)
    }

    /// As [`Sweep::from_file`] for case text whose height maps lie in `base_dir`.
    pub fn new(case_text: &str, base_dir: &Path, vary: &[String]) -> Result<Sweep, SweepError> {
        let spec = read_spec(case_text, vary)?;
        if spec.axes.is_empty() {
            return Err(SweepError::spec(
                "nothing is varied: give --vary KEY=VALUES or a [sweep] section",
            ));
        }
        let mut sweep = Sweep {
            spec,
            base_dir: base_dir.to_path_buf(),
            ids: Vec::new(),
            maps: MapCache::default(),
            case_bytes: Vec::new(),
        };
        sweep.ids = (0..sweep.len()).map(|k| sweep.make_id(k)).collect();
        sweep.check_levels()?;
        sweep.check_cases()?;
        Ok(sweep)
    }

    /// Number of cases.
    pub fn len(&self) -> usize {
        self.spec.axes.iter().map(|a| a.levels.len()).product()
    }

    /// Never true: a sweep has at least one axis of at least one value.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The axes, in order.
    pub fn axes(&self) -> &[Axis] {
        &self.spec.axes
    }

    /// The mu axis of the plot (`[sweep] plot_scale`).
    pub fn plot_scale(&self) -> PlotScale {
        self.spec.plot_scale
    }

    /// The base case without `[sweep]`, as TOML text.
    pub fn base_text(&self) -> String {
        toml::to_string(&self.spec.base).unwrap_or_default()
    }

    /// The stable id of case `index`.
    pub fn id(&self, index: usize) -> &str {
        &self.ids[index]
    }

    /// The level of each axis in case `index` (row-major, last axis fastest).
    pub fn levels(&self, index: usize) -> Vec<usize> {
        let mut rest = index;
        let mut levels = vec![0; self.spec.axes.len()];
        for (a, axis) in self.spec.axes.iter().enumerate().rev() {
            levels[a] = rest % axis.levels.len();
            rest /= axis.levels.len();
        }
        levels
    }

    /// The labels of case `index`'s values, one per axis.
    pub fn labels(&self, index: usize) -> Vec<String> {
        self.levels(index)
            .iter()
            .zip(&self.spec.axes)
            .map(|(&l, a)| a.levels[l].label.clone())
            .collect()
    }

    /// `key = value, ...` for messages.
    pub fn describe(&self, index: usize) -> String {
        self.spec
            .axes
            .iter()
            .zip(self.labels(index))
            .map(|(a, l)| format!("{} = {l}", a.name))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The full case-file text of case `index`.
    pub fn case_text(&self, index: usize) -> String {
        let mut table = self.spec.base.clone();
        for (a, &l) in self.levels(index).iter().enumerate() {
            for (key, value) in &self.spec.axes[a].levels[l].set {
                // Checked when the sweep was made.
                let _ = apply(&mut table, key, value);
            }
        }
        toml::to_string(&table).unwrap_or_default()
    }

    /// Parses case `index` with the library's case-file rules.
    pub fn parse_case(&self, index: usize) -> thirdbody::Result<CaseFile> {
        self.parse_text(&self.case_text(index))
    }

    fn parse_text(&self, text: &str) -> thirdbody::Result<CaseFile> {
        parse_case_file(text, &mut |file, cell| {
            self.maps.load(&self.base_dir, file, cell)
        })
    }

    fn make_id(&self, index: usize) -> String {
        let mut canonical = String::new();
        for (a, &l) in self.levels(index).iter().enumerate() {
            let level = &self.spec.axes[a].levels[l];
            canonical.push_str(&format!("{}={}\n", self.spec.axes[a].name, level.label));
            for (key, value) in &level.set {
                let v = match value {
                    KeyValue::Remove => "none".to_string(),
                    KeyValue::Set(v) => serde_json::to_string(v).unwrap_or_default(),
                };
                canonical.push_str(&format!("  {key}={v}\n"));
            }
        }
        let width = (self.len().saturating_sub(1)).to_string().len().max(4);
        format!("{index:0width$}-{:08x}", fnv1a32(canonical.as_bytes()))
    }

    /// Errors that depend on one value alone (an unknown key, a value of the wrong
    /// type, a law that does not exist) are reported against that value, before the
    /// product is checked.
    fn check_levels(&self) -> Result<(), SweepError> {
        for axis in &self.spec.axes {
            for level in &axis.levels {
                let mut table = self.spec.base.clone();
                for (key, value) in &level.set {
                    apply(&mut table, key, value)
                        .map_err(|m| SweepError::key(&place(axis, &level.label), m))?;
                }
                let text = toml::to_string(&table).unwrap_or_default();
                if let Err(thirdbody::Error::Parse(message)) = self.parse_text(&text) {
                    return Err(SweepError::key(
                        &place(axis, &level.label),
                        strip_line(&message),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Every case of the product must be a valid case; records each one's memory.
    fn check_cases(&mut self) -> Result<(), SweepError> {
        let mut case_bytes = Vec::with_capacity(self.len());
        for index in 0..self.len() {
            let parsed = self.parse_case(index).map_err(|e| match e {
                thirdbody::Error::Parse(m) => strip_line(&m).to_string(),
                other => other.to_string(),
            });
            let checked = parsed.and_then(|file| {
                crate::geometry::check(&file.case, file.stress.as_ref()).map(|()| file)
            });
            match checked {
                Ok(file) => case_bytes.push(crate::memory::estimated_bytes(
                    &file.case,
                    file.stress.as_ref(),
                )),
                Err(message) => {
                    return Err(SweepError::Case {
                        index,
                        settings: self.describe(index),
                        message,
                    });
                }
            }
        }
        self.case_bytes = case_bytes;
        Ok(())
    }

    /// Refuses the cases `mine` says are this run's when the largest of them, solved
    /// by `workers` at once, would not fit in `available` bytes.
    pub fn check_memory(
        &self,
        mine: impl Fn(usize) -> bool,
        workers: usize,
        available: Option<f64>,
    ) -> Result<(), SweepError> {
        let count = (0..self.len()).filter(|&k| mine(k)).count();
        let largest = (0..self.len())
            .filter(|&k| mine(k))
            .max_by(|&a, &b| self.case_bytes[a].total_cmp(&self.case_bytes[b]));
        let Some(index) = largest else {
            return Ok(());
        };
        // Parsed once more: the message names the largest case's grid or stresses.
        let file = self
            .parse_case(index)
            .map_err(|e| SweepError::spec(e.to_string()))?;
        let at_once = workers.clamp(1, count.max(1));
        crate::memory::check(&file.case, file.stress.as_ref(), at_once, available).map_err(|m| {
            SweepError::spec(format!(
                "sweep case {index} ({}), the largest, with {at_once} cases solved at once: \
                 {m} (fewer --threads, or a smaller grid)",
                self.describe(index)
            ))
        })
    }
}

fn place(axis: &Axis, label: &str) -> String {
    if axis.name == VARIANT_AXIS {
        format!("[sweep.variants.{label}]")
    } else {
        format!("--vary {}={label}", axis.name)
    }
}

/// `line 12 (layer.foo): unknown field ...` -> `unknown field ...`: line numbers of a
/// generated case text mean nothing to the user.
fn strip_line(message: &str) -> &str {
    let Some(rest) = message.strip_prefix("line ") else {
        return message;
    };
    let rest = rest.trim_start_matches(|c: char| c.is_ascii_digit());
    let rest = match rest.strip_prefix(" (") {
        Some(r) => r.split_once(')').map_or(r, |(_, after)| after),
        None => rest,
    };
    rest.strip_prefix(": ").unwrap_or(message)
}

/// 32-bit FNV-1a: a hash that is the same on every platform and Rust version.
fn fnv1a32(bytes: &[u8]) -> u32 {
    bytes.iter().fold(0x811c_9dc5u32, |h, &b| {
        (h ^ u32::from(b)).wrapping_mul(0x0100_0193)
    })
}

/// Height maps by (file, cell size), read once per sweep.
#[derive(Debug, Default)]
struct MapCache(Mutex<HashMap<(String, u64), HeightMap>>);

impl MapCache {
    fn load(&self, base: &Path, file: &str, cell: f64) -> thirdbody::Result<HeightMap> {
        let key = (file.to_string(), cell.to_bits());
        if let Some(map) = self.0.lock().ok().and_then(|m| m.get(&key).cloned()) {
            return Ok(map);
        }
        let map = crate::heightmap::load(base, file, cell)?;
        if let Ok(mut maps) = self.0.lock() {
            maps.insert(key, map.clone());
        }
        Ok(map)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sweep tests' base case (shared with the command line's).
    const BASE: &str = include_str!("../../tests/data/sweep_base.toml");

    fn sweep(args: &[&str]) -> Result<Sweep, SweepError> {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        Sweep::new(BASE, Path::new("."), &args)
    }

    #[test]
    fn the_product_is_row_major_with_the_last_axis_fastest() {
        let s = sweep(&["velocity=1e-4,1e-3,1e-2", "p0=0.0025,0.005"]).unwrap();
        assert_eq!(s.len(), 6);
        let labels: Vec<Vec<String>> = (0..6).map(|k| s.labels(k)).collect();
        assert_eq!(labels[0], ["0.0001", "0.0025"]);
        assert_eq!(labels[1], ["0.0001", "0.005"]);
        assert_eq!(labels[2], ["0.001", "0.0025"]);
        assert_eq!(labels[5], ["0.01", "0.005"]);
        let case = s.parse_case(3).unwrap().case;
        assert_eq!(case.loading.velocity, Some(1e-3));
        assert_eq!(
            case.layer.unwrap().law,
            thirdbody::ComplianceLaw::Sigmoid {
                delta: 0.5,
                p0: 0.005
            }
        );
        assert_eq!(s.describe(3), "loading.velocity = 0.001, layer.p0 = 0.005");
    }

    #[test]
    fn ids_are_stable_distinct_and_sortable() {
        let s = sweep(&["velocity=1e-4..1e-1:8", "p0=0.0025,0.005,0.0075"]).unwrap();
        let again = sweep(&["velocity=1e-4..1e-1:8", "p0=0.0025,0.005,0.0075"]).unwrap();
        let ids: Vec<&str> = (0..s.len()).map(|k| s.id(k)).collect();
        assert!(ids.iter().enumerate().all(|(k, id)| *id == again.id(k)));
        assert!(
            ids[0].starts_with("0000-") && ids[0].len() == 13,
            "{}",
            ids[0]
        );
        assert!(ids[23].starts_with("0023-"));
        let mut sorted = ids.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted, ids);
        // A different value at the same index gets a different hash.
        let other = sweep(&["velocity=1e-4..1e-1:8", "p0=0.0025,0.005,0.0076"]).unwrap();
        assert_eq!(other.id(0), s.id(0));
        assert_ne!(other.id(2), s.id(2));
    }

    #[test]
    fn invalid_cases_are_refused_before_anything_runs() {
        let e = sweep(&["layer.colour=1,2"]).unwrap_err().to_string();
        assert!(
            e.starts_with("--vary layer.colour=1: unknown field `colour`, expected one of"),
            "{e}"
        );
        let e = sweep(&["layer.law=sigmoid,cubic"]).unwrap_err().to_string();
        assert!(
            e.starts_with("--vary layer.law=cubic: unknown variant `cubic`"),
            "{e}"
        );
        let e = sweep(&["delta=0.5,2"]).unwrap_err().to_string();
        assert_eq!(
            e,
            "sweep case 1 (layer.delta = 2): layer.delta = 2 is not allowed: 0 <= delta <= 1"
        );
        // The linear law with the sigmoid's delta and p0 still in the case.
        let e = sweep(&["layer.law=sigmoid,linear"])
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("sweep case 1 (layer.law = linear): field layer.delta is not used"),
            "{e}"
        );
        let e = sweep(&[]).unwrap_err().to_string();
        assert!(e.contains("nothing is varied"), "{e}");
    }

    #[test]
    fn strip_line_keeps_the_message() {
        assert_eq!(strip_line("line 3 (a.b): bad"), "bad");
        assert_eq!(strip_line("line 3: bad"), "bad");
        assert_eq!(strip_line("bad"), "bad");
    }
}
