//! The value syntax of one swept key, as written after `--vary KEY=` or as a string in
//! the case file's `[sweep.vary]` table (docs/sweeps.md): a comma-separated list of
//! items, each one
//!
//! * `none`: the key is removed from the case;
//! * a TOML value: `0.005`, `1e-3`, `inf`, `128`, `"linear"`, `[64, 64]`, `true`;
//! * a range `a..b:n` of n >= 2 log-spaced numbers from a to b (both > 0, ends
//!   included exactly), or `a..b:n:lin` for linearly spaced ones;
//! * anything else: a bare string, e.g. `linear`.
//!
//! Commas inside brackets or quotes do not split items. Items keep their order; a
//! value given twice in one list is an error (it would make two identical cases).

use toml::Value;

/// One value of a swept key: a TOML value, or the removal of the key.
#[derive(Debug, Clone, PartialEq)]
pub enum KeyValue {
    /// The key is set to this value.
    Set(Value),
    /// The key is removed from the case.
    Remove,
}

impl KeyValue {
    /// How the value is shown in `results.csv`, plot legends and messages: numbers in
    /// their shortest round-trip form (`0.0001`, `2.5e-5`), strings without quotes,
    /// arrays and tables as inline TOML, `none` for a removal.
    pub fn label(&self) -> String {
        match self {
            KeyValue::Remove => "none".to_string(),
            KeyValue::Set(v) => value_label(v),
        }
    }

    /// The value as a number, if it is one.
    pub fn number(&self) -> Option<f64> {
        match self {
            KeyValue::Set(Value::Float(x)) => Some(*x),
            KeyValue::Set(Value::Integer(n)) => Some(*n as f64),
            _ => None,
        }
    }
}

/// See [`KeyValue::label`].
pub fn value_label(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        Value::Float(x) => float_label(*x),
        Value::Integer(n) => n.to_string(),
        Value::Boolean(b) => b.to_string(),
        other => {
            let mut t = toml::Table::new();
            t.insert("v".into(), other.clone());
            let text = toml::to_string(&t).unwrap_or_default();
            text.trim()
                .strip_prefix("v = ")
                .unwrap_or(text.trim())
                .to_string()
        }
    }
}

/// Shortest round-trip decimal form of a float (`1e-4` -> `0.0001`, `2.5e-5`), as
/// serde_json writes it; `inf`, `-inf` and `nan` as TOML spells them.
pub fn float_label(x: f64) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf" } else { "-inf" }.into();
    }
    serde_json::Number::from_f64(x).map_or_else(|| x.to_string(), |n| n.to_string())
}

/// Values of one key and whether they came from log-spaced ranges only.
#[derive(Debug, Clone, PartialEq)]
pub struct ValueList {
    /// The values in the order written.
    pub values: Vec<KeyValue>,
    /// Every item was a log-spaced range (a hint for a log axis in plots).
    pub log_spaced: bool,
}

/// Parses the value syntax of one key (see the module documentation). The error is a
/// message without the key, for the caller to prefix.
pub fn parse_values(text: &str) -> Result<ValueList, String> {
    let items = split_items(text)?;
    if items.iter().all(|s| s.trim().is_empty()) {
        return Err("no values given (write e.g. KEY=1,2,3 or KEY=1e-4..1e-1:8)".into());
    }
    let mut values = Vec::new();
    let mut log_spaced = true;
    for item in items {
        let item = item.trim();
        if item.is_empty() {
            return Err(format!("empty item in `{text}` (two commas in a row?)"));
        }
        match parse_item(item)? {
            Item::One(v) => {
                log_spaced = false;
                values.push(v);
            }
            Item::Range { values: r, log } => {
                log_spaced &= log;
                values.extend(r.into_iter().map(|x| KeyValue::Set(Value::Float(x))));
            }
        }
    }
    check_distinct(&values)?;
    Ok(ValueList { values, log_spaced })
}

/// Refuses a value given twice (by its label, or by its number: `1` and `1.0` count
/// as the same). O(n log n): a sweep axis of a million values is checked at once.
pub fn check_distinct(values: &[KeyValue]) -> Result<(), String> {
    let twice = |label: String| {
        Err(format!(
            "the value {label} is given twice (each value makes one case)"
        ))
    };
    let mut labels = std::collections::HashSet::with_capacity(values.len());
    for v in values {
        let label = v.label();
        if !labels.insert(label.clone()) {
            return twice(label);
        }
    }
    let mut numbers: Vec<(f64, usize)> = values
        .iter()
        .enumerate()
        .filter_map(|(k, v)| v.number().map(|x| (x, k)))
        .collect();
    numbers.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Equal numbers are neighbours after sorting (-0.0 and 0.0 too: they are
    // adjacent in total order and equal under ==).
    if let Some(w) = numbers.windows(2).find(|w| w[0].0 == w[1].0) {
        let k = w[0].1.max(w[1].1);
        return twice(values[k].label());
    }
    Ok(())
}

enum Item {
    One(KeyValue),
    Range { values: Vec<f64>, log: bool },
}

fn parse_item(item: &str) -> Result<Item, String> {
    if item == "none" {
        return Ok(Item::One(KeyValue::Remove));
    }
    if let Some(v) = toml_value(item) {
        return Ok(Item::One(KeyValue::Set(v)));
    }
    if item.contains("..") {
        return parse_range(item);
    }
    if item.starts_with(['"', '\'', '[', '{']) {
        return Err(format!("`{item}` is not a valid TOML value"));
    }
    Ok(Item::One(KeyValue::Set(Value::String(item.to_string()))))
}

/// The item as a TOML value (`0.5`, `"linear"`, `[64, 64]`), if it is one.
fn toml_value(item: &str) -> Option<Value> {
    let table: toml::Table = toml::from_str(&format!("v = {item}")).ok()?;
    table.get("v").cloned()
}

/// Most values one range may give (each is a case; 10^5 cases of a 128² solve are
/// about three hours on two cores).
pub const MAX_RANGE_VALUES: usize = 100_000;

/// `a..b:n` (log-spaced) or `a..b:n:lin` / `a..b:n:log`.
fn parse_range(item: &str) -> Result<Item, String> {
    let form = "a range is written a..b:n (n log-spaced values, a, b > 0) or a..b:n:lin";
    let (ends, rest) = item
        .split_once(':')
        .ok_or_else(|| format!("`{item}`: the number of values is missing; {form}"))?;
    let (count, spacing) = match rest.split_once(':') {
        Some((n, s)) => (n, s.trim()),
        None => (rest, "log"),
    };
    let log = match spacing {
        "log" => true,
        "lin" => false,
        other => {
            return Err(format!(
                "`{item}`: unknown spacing `{other}`; use :lin or :log (the default)"
            ))
        }
    };
    let (a, b) = ends
        .split_once("..")
        .ok_or_else(|| format!("`{item}`: {form}"))?;
    let number = |s: &str, what: &str| -> Result<f64, String> {
        let s = s.trim();
        match s.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(format!(
                "`{item}`: the {what} end `{s}` is not a finite number; {form}"
            )),
        }
    };
    let (a, b) = (number(a, "first")?, number(b, "last")?);
    let n: usize = count.trim().parse().map_err(|_| {
        format!(
            "`{item}`: the number of values `{}` is not a whole number; {form}",
            count.trim()
        )
    })?;
    if n > MAX_RANGE_VALUES {
        return Err(format!(
            "`{item}`: {n} values is more than a range may give ({MAX_RANGE_VALUES}); a \
             sweep of that size is a job array's work: split it with --shard or give fewer"
        ));
    }
    if n < 2 {
        return Err(format!(
            "`{item}`: a range of {n} value{} is empty or degenerate; give n >= 2 (or list \
             the single value)",
            if n == 1 { "" } else { "s" }
        ));
    }
    if a == b {
        return Err(format!(
            "`{item}`: the range is empty (both ends are {a}); give two different ends"
        ));
    }
    if log && (a <= 0.0 || b <= 0.0) {
        return Err(format!(
            "`{item}`: a log-spaced range needs both ends > 0; use a..b:n:lin for a linear one"
        ));
    }
    let last = (n - 1) as f64;
    let values = (0..n)
        .map(|k| {
            if k == 0 {
                a
            } else if k == n - 1 {
                b
            } else if log {
                a * (b / a).powf(k as f64 / last)
            } else {
                a + (b - a) * (k as f64 / last)
            }
        })
        .collect();
    Ok(Item::Range { values, log })
}

/// Splits on commas outside brackets, braces and quotes.
fn split_items(text: &str) -> Result<Vec<&str>, String> {
    let mut items = Vec::new();
    let (mut depth, mut quote, mut start) = (0i32, None::<char>, 0);
    for (k, c) in text.char_indices() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '[' | '{') => depth += 1,
            (None, ']' | '}') => depth -= 1,
            (None, ',') if depth == 0 => {
                items.push(&text[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    if quote.is_some() || depth != 0 {
        return Err(format!("`{text}` has an unclosed quote or bracket"));
    }
    items.push(&text[start..]);
    Ok(items)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(text: &str) -> Vec<String> {
        parse_values(text)
            .unwrap()
            .values
            .iter()
            .map(KeyValue::label)
            .collect()
    }

    #[test]
    fn lists_of_numbers_strings_arrays_and_none() {
        assert_eq!(labels("0.0025, 0.005,1e-3"), ["0.0025", "0.005", "0.001"]);
        assert_eq!(labels("linear,sigmoid"), ["linear", "sigmoid"]);
        assert_eq!(labels("\"a,b\",c"), ["a,b", "c"]);
        assert_eq!(labels("[64, 64],[128,128]"), ["[64, 64]", "[128, 128]"]);
        assert_eq!(labels("none,0.1,inf"), ["none", "0.1", "inf"]);
        assert_eq!(labels("128"), ["128"]);
        let v = parse_values("128").unwrap();
        assert_eq!(v.values[0], KeyValue::Set(Value::Integer(128)));
        assert!(!v.log_spaced);
    }

    #[test]
    fn log_ranges_include_both_ends_exactly() {
        let v = parse_values("1e-4..1e-1:8").unwrap();
        assert!(v.log_spaced);
        let x: Vec<f64> = v.values.iter().map(|v| v.number().unwrap()).collect();
        assert_eq!(x.len(), 8);
        assert_eq!(x[0], 1e-4);
        assert_eq!(x[7], 1e-1);
        for w in x.windows(2) {
            // Ratio 10^(3/7) between neighbours.
            assert!((w[1] / w[0] - 10f64.powf(3.0 / 7.0)).abs() < 1e-12);
        }
        // Decreasing ranges are allowed and keep their order.
        let v = parse_values("1..0.01:3").unwrap();
        let x: Vec<f64> = v.values.iter().map(|v| v.number().unwrap()).collect();
        assert_eq!(x[0], 1.0);
        assert!((x[1] - 0.1).abs() < 1e-15);
        assert_eq!(x[2], 0.01);
    }

    #[test]
    fn linear_ranges_and_mixed_lists() {
        let v = parse_values("0..1:5:lin").unwrap();
        assert!(!v.log_spaced);
        assert_eq!(
            v.values.iter().map(KeyValue::label).collect::<Vec<_>>(),
            ["0.0", "0.25", "0.5", "0.75", "1.0"]
        );
        let v = parse_values("1e-3..1e-2:2,0.5").unwrap();
        assert!(!v.log_spaced);
        assert_eq!(v.values.len(), 3);
    }

    #[test]
    fn bad_value_lists_are_explained() {
        let err = |t: &str| parse_values(t).unwrap_err();
        assert!(err("").contains("no values given"), "{}", err(""));
        assert!(err("1,,2").contains("empty item"));
        assert!(err("1e-4..1e-1:0").contains("empty or degenerate"));
        assert!(err("1e-4..1e-1:1").contains("n >= 2"));
        assert!(err("1e-4..1e-1").contains("number of values is missing"));
        assert!(err("0..1e-1:4").contains("log-spaced range needs both ends > 0"));
        assert!(err("-1..1:4").contains("a..b:n:lin"));
        assert!(err("1..1:4").contains("range is empty"));
        assert!(err("1..abc:4").contains("the last end `abc` is not a finite number"));
        assert!(err("1..2:x").contains("`x` is not a whole number"));
        assert!(err("1..2:3:cubic").contains("unknown spacing `cubic`"));
        assert!(err("0.1,0.1").contains("0.1 is given twice"));
        assert!(err("1,1.0").contains("given twice"));
        assert!(err("0.0,-0.0").contains("given twice"));
        assert!(err("1e-3..1e-1:100000000").contains("more than a range may give"));
        assert!(err("[1, 2").contains("unclosed"));
        assert!(err("\"abc").contains("unclosed"));
    }
}
