//! What a sweep varies (docs/sweeps.md): the axes of its Cartesian product, read from
//! the case file's `[sweep]` section and the command line's `--vary KEY=VALUES`.
//!
//! An axis is either one case-file key (`loading.velocity`) with its list of values,
//! or the `variant` axis: named sets of overrides from `[sweep.variants.NAME]` that
//! change several keys at once (the linear law beside sigmoid ones, which must also
//! drop `delta` and `p0`). Keys are the case file's dotted keys; a key without a dot is
//! accepted when exactly one key of the base case ends in it (`velocity` means
//! `loading.velocity`). `--vary` replaces a key's values from the file or adds an
//! axis. Axes keep their order: the variant axis first, then the file's `vary` keys,
//! then new `--vary` keys; the first axis varies slowest in the product.

use toml::{Table, Value};

use super::plot_scale::PlotScale;
use super::values::{check_distinct, parse_values, value_label, KeyValue};
use super::SweepError;

/// The name of the axis of `[sweep.variants]`.
pub const VARIANT_AXIS: &str = "variant";

/// One value of an axis: what it is called and which keys it sets.
#[derive(Debug, Clone, PartialEq)]
pub struct Level {
    /// As shown in `results.csv` and plot legends.
    pub label: String,
    /// Dotted keys and their values, in order.
    pub set: Vec<(String, KeyValue)>,
}

impl Level {
    /// The level's number when it sets one key to a number.
    pub fn number(&self) -> Option<f64> {
        match self.set.as_slice() {
            [(_, v)] => v.number(),
            _ => None,
        }
    }
}

/// One dimension of the product.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The dotted key, or [`VARIANT_AXIS`].
    pub name: String,
    /// Its values, in order.
    pub levels: Vec<Level>,
    /// Every value came from log-spaced ranges.
    pub log_spaced: bool,
}

/// The base case (without `[sweep]`) and the axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    /// The case file's table without its `[sweep]` section.
    pub base: Table,
    /// The axes of the product.
    pub axes: Vec<Axis>,
    /// The mu axis of the plot (`[sweep] plot_scale`).
    pub plot_scale: PlotScale,
}

/// Reads the case text's `[sweep]` section and the `--vary` arguments.
pub fn read_spec(case_text: &str, vary: &[String]) -> Result<Spec, SweepError> {
    let mut base: Table = toml::from_str(case_text).map_err(|e| {
        let line = e.span().map(|s| {
            case_text[..s.start.min(case_text.len())]
                .matches('\n')
                .count()
                + 1
        });
        let message = e.message().trim().replace('\n', " ");
        SweepError::spec(match line {
            Some(l) => format!("the case file is not valid TOML: line {l}: {message}"),
            None => format!("the case file is not valid TOML: {message}"),
        })
    })?;
    let section = match base.remove("sweep") {
        None => Table::new(),
        Some(Value::Table(t)) => t,
        Some(_) => return Err(SweepError::spec("[sweep] must be a section (a table)")),
    };
    let known = leaf_keys(&base, "");
    let mut axes = Vec::new();
    for (key, _) in section.iter() {
        if !["vary", "variants", "plot_scale"].contains(&key.as_str()) {
            return Err(SweepError::spec(format!(
                "[sweep] has an unknown key `{key}`; allowed: vary, variants, plot_scale"
            )));
        }
    }
    let plot_scale = match section.get("plot_scale") {
        None => PlotScale::default(),
        Some(v) => v.as_str().and_then(PlotScale::from_name).ok_or_else(|| {
            SweepError::spec(format!(
                "[sweep] plot_scale = {v} is not a plot scale; allowed: {}",
                PlotScale::NAMES.map(|n| format!("\"{n}\"")).join(", ")
            ))
        })?,
    };
    if let Some(variants) = section.get("variants") {
        axes.push(variant_axis(variants, &known)?);
    }
    let mut file_keys = Vec::new();
    if let Some(vary) = section.get("vary") {
        let Value::Table(vary) = vary else {
            return Err(SweepError::spec(
                "[sweep] vary must be a table of KEY = \"VALUES\" or KEY = [values]",
            ));
        };
        for (key, value) in flatten(vary, "") {
            let where_ = format!("[sweep.vary] {key}");
            let key = resolve_key(&known, &key).map_err(|m| SweepError::key(&where_, m))?;
            let (values, log_spaced) = match &value {
                Value::String(s) => {
                    let v = parse_values(s).map_err(|m| SweepError::key(&where_, m))?;
                    (v.values, v.log_spaced)
                }
                Value::Array(items) => {
                    let v: Vec<KeyValue> = items.iter().map(literal).collect();
                    if v.is_empty() {
                        return Err(SweepError::key(&where_, "the list of values is empty"));
                    }
                    check_distinct(&v).map_err(|m| SweepError::key(&where_, m))?;
                    (v, false)
                }
                other => (vec![literal(other)], false),
            };
            if file_keys.contains(&key) {
                return Err(SweepError::key(&where_, "the key is given twice"));
            }
            file_keys.push(key.clone());
            axes.push(key_axis(key, values, log_spaced));
        }
    }
    let mut cli_keys: Vec<String> = Vec::new();
    for arg in vary {
        let (key, text) = arg.split_once('=').ok_or_else(|| {
            SweepError::key(
                &format!("--vary {arg}"),
                "write KEY=VALUES, e.g. loading.velocity=1e-4..1e-1:8 or layer.p0=0.0025,0.005",
            )
        })?;
        let where_ = format!("--vary {}", key.trim());
        let key = resolve_key(&known, key.trim()).map_err(|m| SweepError::key(&where_, m))?;
        let values = parse_values(text).map_err(|m| SweepError::key(&where_, m))?;
        if cli_keys.contains(&key) {
            return Err(SweepError::key(
                &where_,
                format!("{key} is varied twice; give all its values in one --vary"),
            ));
        }
        cli_keys.push(key.clone());
        let axis = key_axis(key.clone(), values.values, values.log_spaced);
        match axes.iter_mut().find(|a| a.name == key) {
            Some(existing) => *existing = axis,
            None => axes.push(axis),
        }
    }
    check_axes(&axes, &base)?;
    Ok(Spec {
        base,
        axes,
        plot_scale,
    })
}

fn key_axis(key: String, values: Vec<KeyValue>, log_spaced: bool) -> Axis {
    Axis {
        levels: values
            .into_iter()
            .map(|v| Level {
                label: v.label(),
                set: vec![(key.clone(), v)],
            })
            .collect(),
        name: key,
        log_spaced,
    }
}

/// A value of the case file as a sweep value: the string "none" removes the key.
fn literal(v: &Value) -> KeyValue {
    match v {
        Value::String(s) if s == "none" => KeyValue::Remove,
        other => KeyValue::Set(other.clone()),
    }
}

fn variant_axis(variants: &Value, known: &[String]) -> Result<Axis, SweepError> {
    let needs = "[sweep.variants] must hold sections [sweep.variants.NAME] of KEY = value";
    let Value::Table(variants) = variants else {
        return Err(SweepError::spec(needs));
    };
    if variants.is_empty() {
        return Err(SweepError::spec(
            "[sweep.variants] is empty; give at least one variant",
        ));
    }
    let mut levels = Vec::new();
    for (name, set) in variants.iter() {
        let where_ = format!("[sweep.variants.{name}]");
        let Value::Table(set) = set else {
            return Err(SweepError::spec(format!("{where_}: {needs}")));
        };
        let mut keys = Vec::new();
        for (key, value) in flatten(set, "") {
            let key = resolve_key(known, &key).map_err(|m| SweepError::key(&where_, m))?;
            if keys.iter().any(|(k, _)| *k == key) {
                return Err(SweepError::key(&where_, format!("{key} is set twice")));
            }
            keys.push((key, literal(&value)));
        }
        levels.push(Level {
            label: name.clone(),
            set: keys,
        });
    }
    Ok(Axis {
        name: VARIANT_AXIS.to_string(),
        levels,
        log_spaced: false,
    })
}

/// Refuses a key set by two axes and a non-number where the base case has a number.
fn check_axes(axes: &[Axis], base: &Table) -> Result<(), SweepError> {
    for (a, axis) in axes.iter().enumerate() {
        for level in &axis.levels {
            for (key, value) in &level.set {
                if let Some(other) = axes[..a]
                    .iter()
                    .chain(&axes[a + 1..])
                    .find(|o| o.levels.iter().any(|l| l.set.iter().any(|(k, _)| k == key)))
                {
                    return Err(SweepError::key(
                        &axis_place(axis),
                        format!(
                            "{key} is also set by {}; a key may be varied by one axis only",
                            axis_place(other)
                        ),
                    ));
                }
                let base_value = get(base, key);
                if let (Some(b @ (Value::Float(_) | Value::Integer(_))), KeyValue::Set(v)) =
                    (base_value, value)
                {
                    if !matches!(v, Value::Float(_) | Value::Integer(_)) {
                        return Err(SweepError::key(
                            &axis_place(axis),
                            format!(
                                "`{}` is not a number ({key} is a number, {} in the case file)",
                                value_label(v),
                                value_label(b)
                            ),
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

fn axis_place(axis: &Axis) -> String {
    if axis.name == VARIANT_AXIS {
        "[sweep.variants]".to_string()
    } else {
        format!("--vary {}", axis.name)
    }
}

/// Every key of `table` that is not itself a table, dotted (`loading.velocity`).
fn leaf_keys(table: &Table, prefix: &str) -> Vec<String> {
    flatten(table, prefix).into_iter().map(|(k, _)| k).collect()
}

/// Non-table entries of `table` by dotted key, in order.
fn flatten(table: &Table, prefix: &str) -> Vec<(String, Value)> {
    let mut out = Vec::new();
    for (k, v) in table.iter() {
        let key = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            Value::Table(t) => out.extend(flatten(t, &key)),
            // An array of tables (`[[body.layers]]`): `body.layers[0].thickness`, ...
            Value::Array(list) if !list.is_empty() && list.iter().all(Value::is_table) => {
                for (i, entry) in list.iter().enumerate() {
                    if let Value::Table(t) = entry {
                        out.extend(flatten(t, &format!("{key}[{i}]")));
                    }
                }
            }
            other => out.push((key, other.clone())),
        }
    }
    out
}

/// A key part `name[k]`: the name and the list index.
fn indexed(part: &str) -> Option<(&str, usize)> {
    let (name, rest) = part.split_once('[')?;
    let k = rest.strip_suffix(']')?.parse().ok()?;
    Some((name, k))
}

/// The value at a dotted key, if present (`layer.branch_times[0]`: an entry of a
/// list; `body.layers[1].young`: a key of a table in an array of tables).
pub fn get<'a>(table: &'a Table, key: &str) -> Option<&'a Value> {
    let parts: Vec<&str> = key.split('.').collect();
    let (last, sections) = parts.split_last()?;
    let mut t = table;
    for part in sections {
        t = match indexed(part) {
            Some((name, k)) => t.get(name)?.as_array()?.get(k)?.as_table()?,
            None => t.get(*part)?.as_table()?,
        };
    }
    match indexed(last) {
        Some((name, k)) => t.get(name)?.as_array()?.get(k),
        None => t.get(*last),
    }
}

/// Sets or removes the value at a dotted key, creating sections as needed.
pub fn apply(table: &mut Table, key: &str, value: &KeyValue) -> Result<(), String> {
    let parts: Vec<&str> = key.split('.').collect();
    let (last, sections) = parts.split_last().ok_or("empty key")?;
    let mut t = table;
    for (k, part) in sections.iter().enumerate() {
        if let Some((name, i)) = indexed(part) {
            // A table of an array of tables: it must exist (a sweep does not add layers).
            let entry = t
                .get_mut(name)
                .and_then(Value::as_array_mut)
                .and_then(|list| list.get_mut(i));
            t = match entry {
                Some(Value::Table(inner)) => inner,
                _ => {
                    return Err(format!(
                        "{key} names entry {i} of {}, which the case does not have",
                        parts[..k]
                            .iter()
                            .chain([&name])
                            .copied()
                            .collect::<Vec<_>>()
                            .join(".")
                    ))
                }
            };
            continue;
        }
        let entry = t
            .entry(part.to_string())
            .or_insert_with(|| Value::Table(Table::new()));
        t = match entry {
            Value::Table(inner) => inner,
            _ => {
                return Err(format!(
                    "{} is a value, not a section, so {key} cannot be set",
                    parts[..=k].join(".")
                ))
            }
        };
    }
    if let Some((name, k)) = indexed(last) {
        let len = t.get(name).and_then(Value::as_array).map(Vec::len);
        let Some(Value::Array(list)) = t.get_mut(name).filter(|_| len.is_some_and(|n| k < n))
        else {
            return Err(format!(
                "{key} names entry {k} of the list {name}, which {}",
                match len {
                    Some(n) => format!("has {n} entries (counted from 0)"),
                    None => "the case does not have".to_string(),
                }
            ));
        };
        return match value {
            KeyValue::Set(v) => {
                list[k] = v.clone();
                Ok(())
            }
            KeyValue::Remove => Err(format!("{key}: an entry of a list cannot be removed")),
        };
    }
    match value {
        KeyValue::Set(v) => {
            t.insert(last.to_string(), v.clone());
        }
        KeyValue::Remove => {
            t.remove(*last);
        }
    }
    Ok(())
}

/// A dotted key as given, or the one key of the base case that ends in `key`.
fn resolve_key(known: &[String], key: &str) -> Result<String, String> {
    if key.is_empty() {
        return Err("the key is empty; write KEY=VALUES".into());
    }
    if key == "sweep" || key.starts_with("sweep.") {
        return Err("the [sweep] section itself cannot be varied".into());
    }
    if key.contains('.') || known.iter().any(|k| k == key) {
        return Ok(key.to_string());
    }
    let candidates: Vec<&String> = known
        .iter()
        .filter(|k| k.rsplit('.').next() == Some(key))
        .collect();
    match candidates.as_slice() {
        [one] => Ok((*one).clone()),
        [] => Err(format!(
            "unknown key `{key}`: no key of the case is called that; give a dotted key \
             SECTION.KEY (keys of this case: {})",
            known.join(", ")
        )),
        many => Err(format!(
            "ambiguous key `{key}`: it could be {}; give the dotted key",
            many.iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join(" or ")
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sweep tests' base case (shared with the command line's) on a coated body.
    const BASE: &str = concat!(
        include_str!("../../tests/data/sweep_base.toml"),
        "\n[coating]\nyoung = 3.0\npoisson = 0.3\nthickness = 0.02\n"
    );

    fn vary(args: &[&str]) -> Result<Spec, SweepError> {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        read_spec(BASE, &args)
    }

    fn names(spec: &Spec) -> Vec<&str> {
        spec.axes.iter().map(|a| a.name.as_str()).collect()
    }

    #[test]
    fn aliases_resolve_to_the_one_key_that_ends_in_them() {
        let spec = vary(&["velocity=1e-4..1e-1:8", "p0=0.0025,0.005"]).unwrap();
        assert_eq!(names(&spec), ["loading.velocity", "layer.p0"]);
        assert!(spec.axes[0].log_spaced);
        assert_eq!(spec.axes[1].levels[1].label, "0.005");
        assert_eq!(spec.axes[1].levels[1].number(), Some(0.005));
        assert!(get(&spec.base, "layer.p0").is_some());
    }

    #[test]
    fn unknown_ambiguous_duplicate_and_non_numeric_keys_are_refused() {
        let err = |args: &[&str]| vary(args).unwrap_err().to_string();
        let e = err(&["colour=1,2"]);
        assert!(e.starts_with("--vary colour: unknown key `colour`"), "{e}");
        assert!(e.contains("loading.velocity"), "{e}");
        let e = err(&["young=1,2"]);
        assert!(
            e.contains("ambiguous key `young`: it could be substrate.young or coating.young"),
            "{e}"
        );
        let e = err(&["velocity=1e-3", "loading.velocity=1e-2"]);
        assert!(e.contains("loading.velocity is varied twice"), "{e}");
        let e = err(&["velocity=1e-3,fast"]);
        assert_eq!(
            e,
            "--vary loading.velocity: `fast` is not a number (loading.velocity is a number, \
             0.001 in the case file)"
        );
        let e = err(&["velocity"]);
        assert!(e.contains("write KEY=VALUES"), "{e}");
        let e = err(&["velocity="]);
        assert!(e.contains("no values given"), "{e}");
        let e = err(&["sweep.vary=1"]);
        assert!(e.contains("cannot be varied"), "{e}");
    }

    #[test]
    fn the_sweep_section_gives_axes_and_the_command_line_overrides_them() {
        let text = format!(
            "{BASE}\n[sweep.vary]\n\"layer.p0\" = [0.0025, 0.005]\nloading.velocity = \
             \"1e-3,1e-2\"\n[sweep.variants.sigmoid]\n[sweep.variants.linear]\n\
             \"layer.law\" = \"linear\"\nlayer.delta = \"none\"\nlayer.p0 = \"none\"\n"
        );
        // Variant sets the same key as an axis: refused.
        let e = read_spec(&text, &[]).unwrap_err().to_string();
        assert!(e.contains("layer.p0 is also set by"), "{e}");
        let text = text.replace("\"layer.p0\" = [0.0025, 0.005]\n", "");
        let spec = read_spec(&text, &["velocity=1e-4..1e-1:4".into()]).unwrap();
        assert_eq!(names(&spec), ["variant", "loading.velocity"]);
        assert!(spec.base.get("sweep").is_none());
        assert_eq!(spec.axes[1].levels.len(), 4);
        let linear = &spec.axes[0].levels[1];
        assert_eq!(linear.label, "linear");
        assert_eq!(linear.set.len(), 3);
        assert_eq!(linear.set[1], ("layer.delta".to_string(), KeyValue::Remove));
        assert!(spec.axes[0].levels[0].set.is_empty());
        let e = read_spec(&format!("{BASE}\n[sweep]\nvaries = 1\n"), &[])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("unknown key `varies`; allowed: vary, variants, plot_scale"),
            "{e}"
        );
    }

    #[test]
    fn the_plot_scale_is_read_from_the_sweep_section() {
        let with = |line: &str| read_spec(&format!("{BASE}\n[sweep]\n{line}\n"), &[]);
        assert_eq!(vary(&["p0=1,2"]).unwrap().plot_scale, PlotScale::Auto);
        for (name, scale) in [
            ("auto", PlotScale::Auto),
            ("linear", PlotScale::Linear),
            ("log", PlotScale::Log),
        ] {
            let spec = with(&format!("plot_scale = \"{name}\"")).unwrap();
            assert_eq!(spec.plot_scale, scale);
            // Not a key of the case.
            assert!(get(&spec.base, "sweep.plot_scale").is_none());
        }
        // The paper's Fig. 8 keeps a linear mu axis.
        let fig8 = include_str!("../../../../examples/sweeps/paper_fig8.toml");
        assert_eq!(read_spec(fig8, &[]).unwrap().plot_scale, PlotScale::Linear);
        for (bad, shown) in [("\"logarithmic\"", "\"logarithmic\""), ("1", "1")] {
            let e = with(&format!("plot_scale = {bad}"))
                .unwrap_err()
                .to_string();
            assert_eq!(
                e,
                format!(
                    "[sweep] plot_scale = {shown} is not a plot scale; allowed: \"auto\", \
                     \"linear\", \"log\""
                )
            );
        }
    }

    #[test]
    fn apply_sets_and_removes_dotted_keys() {
        let mut t: Table = toml::from_str(BASE).unwrap();
        apply(&mut t, "layer.p0", &KeyValue::Remove).unwrap();
        assert!(get(&t, "layer.p0").is_none());
        // An entry of a list.
        let mut l: Table = toml::from_str("[layer]\nbranch_times = [1.0, 2.0]").unwrap();
        apply(
            &mut l,
            "layer.branch_times[1]",
            &KeyValue::Set(Value::Float(5.0)),
        )
        .unwrap();
        assert_eq!(get(&l, "layer.branch_times[1]"), Some(&Value::Float(5.0)));
        assert_eq!(get(&l, "layer.branch_times[0]"), Some(&Value::Float(1.0)));
        let e = apply(
            &mut l,
            "layer.branch_times[2]",
            &KeyValue::Set(Value::Float(5.0)),
        );
        assert!(e.unwrap_err().contains("has 2 entries"));
        apply(
            &mut t,
            "grid.half_width",
            &KeyValue::Set(toml::Value::Float(0.1)),
        )
        .unwrap();
        assert_eq!(get(&t, "grid.half_width"), Some(&toml::Value::Float(0.1)));
        let e = apply(&mut t, "grid.cells.x", &KeyValue::Remove).unwrap_err();
        assert!(e.contains("grid.cells is a value, not a section"), "{e}");
    }

    #[test]
    fn keys_of_an_array_of_tables_are_indexed() {
        let text = "[body]\nbase = \"rigid\"\nbonding = \"bonded\"\n\
                    [[body.layers]]\nyoung = 3.0\npoisson = 0.3\nthickness = 0.1\n\
                    [[body.layers]]\nyoung = 1.0\npoisson = 0.45\nthickness = 0.5\n";
        let mut t: Table = toml::from_str(text).unwrap();
        let keys = leaf_keys(&t, "");
        assert!(
            keys.contains(&"body.layers[1].thickness".to_string()),
            "{keys:?}"
        );
        assert!(keys.contains(&"body.base".to_string()), "{keys:?}");
        assert_eq!(get(&t, "body.layers[1].young"), Some(&Value::Float(1.0)));
        apply(
            &mut t,
            "body.layers[1].thickness",
            &KeyValue::Set(Value::Float(2.0)),
        )
        .unwrap();
        assert_eq!(
            get(&t, "body.layers[1].thickness"),
            Some(&Value::Float(2.0))
        );
        assert_eq!(
            get(&t, "body.layers[0].thickness"),
            Some(&Value::Float(0.1))
        );
        let e = apply(
            &mut t,
            "body.layers[2].thickness",
            &KeyValue::Set(Value::Float(2.0)),
        )
        .unwrap_err();
        assert!(e.contains("entry 2 of body.layers"), "{e}");
        // The bare key is ambiguous between the layers.
        let e = resolve_key(&keys, "thickness").unwrap_err();
        assert!(
            e.contains("body.layers[0].thickness or body.layers[1].thickness"),
            "{e}"
        );
    }
}
