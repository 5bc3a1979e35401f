//! The solutions of one `reproduce` run: a case several figures use (Figs. 5, 9 and
//! 10 share two; Figs. 7, 11 and 12 the coated ones) is solved once and kept until
//! its last planned use ([`super::catalogue::every_case`]), then dropped, so memory
//! stays at what the remaining figures need. Cases missing from a request are solved
//! in parallel (rayon), each solve on one thread; a solve is deterministic, so a kept
//! solution is the one a new solve would give.

use std::sync::Arc;

use rayon::prelude::*;
use thirdbody::{Case, Parallelism, Solution, SolverParams};

/// Solutions kept for later figures.
pub struct Solutions {
    params: SolverParams,
    /// Each planned case with its uses still to come.
    remaining: Vec<(Case, usize)>,
    /// Solved cases with uses still to come.
    kept: Vec<(Case, Arc<Solution>)>,
}

impl Solutions {
    /// Solutions for a run that will ask for `planned` (one entry per use).
    pub fn new(planned: Vec<Case>) -> Self {
        let mut remaining: Vec<(Case, usize)> = Vec::new();
        for case in planned {
            match remaining.iter_mut().find(|(c, _)| *c == case) {
                Some((_, n)) => *n += 1,
                None => remaining.push((case, 1)),
            }
        }
        Solutions {
            params: SolverParams {
                parallelism: Parallelism::Sequential,
                ..SolverParams::default()
            },
            remaining,
            kept: Vec::new(),
        }
    }

    /// The solution of each case: kept ones reused, the others solved in parallel.
    pub fn solve(&mut self, cases: &[Case]) -> Vec<thirdbody::Result<Arc<Solution>>> {
        let known: Vec<Option<Arc<Solution>>> = cases
            .iter()
            .map(|case| {
                self.kept
                    .iter()
                    .find(|(c, _)| c == case)
                    .map(|(_, s)| s.clone())
            })
            .collect();
        let mut solved: Vec<Option<thirdbody::Result<Solution>>> = cases
            .par_iter()
            .zip(&known)
            .map(|(case, known)| match known {
                Some(_) => None,
                None => Some(thirdbody::solve(case, &self.params)),
            })
            .collect();
        let out: Vec<thirdbody::Result<Arc<Solution>>> = known
            .into_iter()
            .zip(&mut solved)
            .map(|(known, new)| match (known, new.take()) {
                (Some(s), _) => Ok(s),
                (None, Some(new)) => new.map(Arc::new),
                (None, None) => unreachable!("every unknown case is solved"),
            })
            .collect();
        for (case, result) in cases.iter().zip(&out) {
            self.used(case, result.as_ref().ok());
        }
        out
    }

    /// Solutions of cases that must all converge.
    pub fn solve_each(&mut self, cases: &[Case]) -> anyhow::Result<Vec<Arc<Solution>>> {
        self.solve(cases)
            .into_iter()
            .map(|s| s.map_err(anyhow::Error::from))
            .collect()
    }

    /// Counts one use of `case`; keeps its solution while uses remain, drops it after
    /// the last.
    fn used(&mut self, case: &Case, solution: Option<&Arc<Solution>>) {
        let left = match self.remaining.iter_mut().find(|(c, _)| c == case) {
            Some((_, n)) => {
                *n = n.saturating_sub(1);
                *n
            }
            None => 0,
        };
        let at = self.kept.iter().position(|(c, _)| c == case);
        match (left, at, solution) {
            (0, Some(k), _) => {
                self.kept.swap_remove(k);
            }
            (1.., None, Some(s)) => self.kept.push((case.clone(), s.clone())),
            _ => {}
        }
        if left == 0 {
            self.remaining.retain(|(c, _)| c != case);
        }
    }

    /// How many solutions are kept (for tests).
    #[cfg(test)]
    fn kept(&self) -> usize {
        self.kept.len()
    }
}

#[cfg(test)]
mod tests {
    use super::super::{catalogue, Resolution};
    use super::*;

    #[test]
    fn a_shared_case_is_solved_once_and_dropped_after_its_last_use() {
        let r = Resolution {
            cells: 16,
            points: 2,
        };
        let [(_, a), (_, b)] = <[_; 2]>::try_from(catalogue::fig9_10(r)).ok().unwrap();
        let mut s = Solutions::new(vec![a.clone(), b.clone(), a.clone()]);
        let first = s.solve_each(std::slice::from_ref(&a)).unwrap();
        assert_eq!(s.kept(), 1);
        s.solve_each(std::slice::from_ref(&b)).unwrap();
        assert_eq!(s.kept(), 1, "b has no use left");
        let again = s.solve_each(std::slice::from_ref(&a)).unwrap();
        assert!(Arc::ptr_eq(&first[0], &again[0]), "a was not solved again");
        assert_eq!(s.kept(), 0);
    }
}
