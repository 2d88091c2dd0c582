//! A total work budget shared by every curve of one chart, so that no field (tiny cells next to
//! huge ones, overflowing velocities, slow spirals) can keep tracing for minutes.
//!
//! Each streamline half already stops after `max_steps` steps; the budget bounds the sum over all
//! lines and all seeding attempts. Tracing stops cleanly once it is spent, keeping the lines
//! finished so far, and [`StepBudget::exhausted`] tells the caller to say so.

use std::cell::Cell;

/// Largest number of integration steps per chart, over every streamline and separatrix.
pub const MAX_STEPS: u64 = 4_000_000;

/// Largest number of seeding attempts (candidate seeds tried) per chart.
pub const MAX_SEED_ATTEMPTS: u64 = 1_000_000;

/// Largest number of stored points examined for the spacing test per chart: a field whose lines
/// all crowd into one background cell (coordinates spanning 1e-9 to 1e9) would otherwise make
/// every step scan a growing cell, and take hours within the step budget.
pub const MAX_EXAMINED: u64 = 400_000_000;

/// Integration steps, seeding attempts and spacing work left for one chart.
#[derive(Debug)]
pub struct StepBudget {
    steps: Cell<u64>,
    attempts: Cell<u64>,
    examined: Cell<u64>,
    exhausted: Cell<bool>,
}

impl Default for StepBudget {
    fn default() -> Self {
        Self::new(MAX_STEPS, MAX_SEED_ATTEMPTS)
    }
}

impl StepBudget {
    /// A budget of `steps` integration steps and `attempts` seeding attempts.
    pub fn new(steps: u64, attempts: u64) -> Self {
        Self {
            steps: Cell::new(steps),
            attempts: Cell::new(attempts),
            examined: Cell::new(MAX_EXAMINED),
            exhausted: Cell::new(false),
        }
    }

    /// Accounts for `points` stored points examined by a spacing test; `false` (and the budget
    /// marked exhausted) when that exceeds what is left.
    pub fn examine(&self, points: u64) -> bool {
        Self::take(&self.examined, points, &self.exhausted)
    }

    /// Takes one integration step; `false` (and the budget marked exhausted) when none is left.
    pub fn step(&self) -> bool {
        Self::take(&self.steps, 1, &self.exhausted)
    }

    /// Takes one seeding attempt; `false` (and the budget marked exhausted) when none is left.
    pub fn attempt(&self) -> bool {
        Self::take(&self.attempts, 1, &self.exhausted)
    }

    /// Whether tracing was cut short because the budget ran out.
    pub fn exhausted(&self) -> bool {
        self.exhausted.get()
    }

    fn take(left: &Cell<u64>, amount: u64, exhausted: &Cell<bool>) -> bool {
        match left.get().checked_sub(amount) {
            Some(rest) if !exhausted.get() => {
                left.set(rest);
                true
            }
            _ => {
                exhausted.set(true);
                false
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spends_down_and_stays_exhausted() {
        let b = StepBudget::new(2, 1);
        assert!(b.step() && b.step() && !b.exhausted());
        assert!(!b.step() && b.exhausted());
        // Once spent, attempts stop too: the chart stops tracing altogether.
        assert!(!b.attempt());
    }
}
