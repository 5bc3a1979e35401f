//! The case-file keys of a rheology preset as the parser hands them over: each
//! preset declares its keys with their kinds ([`KeyKind`]), the parser reads the
//! values of the keys given ([`KeyValue`]) and the preset takes what it needs from a
//! [`KeyReader`], whose errors name the key as `layer.<key>`.

use crate::error::{Error, Result};

/// What a key's value is in the case file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyKind {
    /// One number (`compliance = 0.02`).
    Number,
    /// A list of numbers (`branch_times = [0.1, 10]`).
    Numbers,
    /// A non-negative integer (`branch_count = 40`).
    Count,
}

/// A key's value as read from the case file.
#[derive(Debug, Clone, PartialEq)]
pub enum KeyValue {
    /// [`KeyKind::Number`].
    Number(f64),
    /// [`KeyKind::Numbers`].
    Numbers(Vec<f64>),
    /// [`KeyKind::Count`].
    Count(usize),
}

/// The keys given for one preset, and the compliance a table law supplies.
#[derive(Debug, Clone, Copy)]
pub struct KeyReader<'a> {
    name: &'static str,
    values: &'a [(&'static str, KeyValue)],
    table_compliance: Option<f64>,
}

impl<'a> KeyReader<'a> {
    /// The keys `values` given to the preset `name`; `table_compliance` is the
    /// table law's first compliance when the preset takes its compliance from it.
    pub fn new(
        name: &'static str,
        values: &'a [(&'static str, KeyValue)],
        table_compliance: Option<f64>,
    ) -> Self {
        KeyReader {
            name,
            values,
            table_compliance,
        }
    }

    /// The preset's name (`rheology = "..."`).
    pub fn name(&self) -> &'static str {
        self.name
    }

    fn value(&self, key: &str) -> Option<&'a KeyValue> {
        self.values.iter().find(|(k, _)| *k == key).map(|(_, v)| v)
    }

    /// The number `key`, if given.
    pub fn number(&self, key: &str) -> Option<f64> {
        match self.value(key)? {
            KeyValue::Number(x) => Some(*x),
            KeyValue::Numbers(_) | KeyValue::Count(_) => None,
        }
    }

    /// The list of numbers `key`, if given.
    pub fn numbers(&self, key: &str) -> Option<Vec<f64>> {
        match self.value(key)? {
            KeyValue::Numbers(x) => Some(x.clone()),
            KeyValue::Number(_) | KeyValue::Count(_) => None,
        }
    }

    /// The count `key`, if given.
    pub fn count(&self, key: &str) -> Option<usize> {
        match self.value(key)? {
            KeyValue::Count(n) => Some(*n),
            KeyValue::Number(_) | KeyValue::Numbers(_) => None,
        }
    }

    /// The number `key`, or a missing-key error saying `why` it is needed.
    pub fn need_number(&self, key: &str, why: &str) -> Result<f64> {
        need(self.number(key), key, why)
    }

    /// The list `key`, or a missing-key error saying `why` it is needed.
    pub fn need_numbers(&self, key: &str, why: &str) -> Result<Vec<f64>> {
        need(self.numbers(key), key, why)
    }

    /// `"a <name> layer needs <what> (> 0)"`, the usual reason.
    pub fn needs(&self, what: &str) -> String {
        format!("a {} layer needs {what} (> 0)", self.name)
    }

    /// The preset's one compliance: the table law's first compliance when the law
    /// is a table (then `compliance` must not be given), else the key `compliance`.
    pub fn compliance_or_table(&self, what: &str) -> Result<f64> {
        match self.table_compliance {
            Some(c0) => {
                if self.value("compliance").is_some() {
                    return Err(Error::UnusedField {
                        field: "layer.compliance".to_string(),
                        why: "law = \"table\" takes its compliances from the table".to_string(),
                    });
                }
                Ok(c0)
            }
            None => self.need_number("compliance", &self.needs(what)),
        }
    }

    /// `branch_times`, one per entry of the list `key` (of `n` entries).
    pub fn branch_times(&self, n: usize, key: &str) -> Result<Vec<f64>> {
        let times = self.need_numbers(
            "branch_times",
            &format!("one time (> 0) per entry of layer.{key}"),
        )?;
        if times.len() != n {
            return Err(Error::invalid(
                "layer.branch_times",
                format!("{} times for {n} branches", times.len()),
                &format!("one time per entry of layer.{key}"),
            ));
        }
        Ok(times)
    }
}

fn need<T>(value: Option<T>, key: &str, why: &str) -> Result<T> {
    value.ok_or_else(|| Error::MissingField {
        field: format!("layer.{key}"),
        why: why.to_string(),
    })
}
