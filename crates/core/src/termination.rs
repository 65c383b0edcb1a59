//! How an iterative method ended: one answer for every contact solver, optimisation and search
//! (argmin's `TerminationReason`, clarabel's `SolverStatus`). A method that stops short is not
//! an error: it returns its last iterate with a [`Termination`] that says why and how far it
//! got; errors are for bad input and for work refused before it starts.

use serde::{Deserialize, Serialize};

use crate::observe::Method;

/// Why a method stopped.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Termination {
    /// The method met its tolerance.
    Converged,
    /// It used its step limit: `measure` is where its convergence measure stood after the
    /// last step, `tolerance` what it had to reach.
    StepLimit {
        /// Steps taken.
        steps: usize,
        /// The convergence measure after the last step.
        measure: f64,
        /// The value it had to reach.
        tolerance: f64,
    },
    /// It could not make progress: a singular system, an interior point that stalled, a
    /// contact set that kept cycling; `reason` says which.
    Stalled {
        /// What went wrong, in words.
        reason: String,
    },
    /// A value became NaN or infinite: the data overflow f64 or the method broke down.
    NonFinite {
        /// The quantity that is not finite.
        field: String,
    },
    /// The elastic displacement exceeds the size of the interface: no small-strain answer
    /// (the moduli, the load or the units are off).
    LargeDisplacement {
        /// The largest elastic displacement \[mm\].
        displacement_mm: f64,
        /// The size of the interface \[mm\].
        size_mm: f64,
    },
    /// The programme has no feasible point; `reason` says which constraints conflict.
    Infeasible {
        /// Why, in words.
        reason: String,
    },
    /// The programme's objective is unbounded; `reason` says what leaves it free.
    Unbounded {
        /// Why, in words.
        reason: String,
    },
    /// An observer asked it to stop after `after` iterations.
    Stopped {
        /// Iterations done.
        after: usize,
    },
    /// A method it runs inside (a contact solve of an optimisation) ended as `termination`.
    Inner {
        /// The inner method.
        method: Method,
        /// How the inner method ended.
        termination: Box<Termination>,
    },
}

impl Termination {
    /// Whether the method met its tolerance.
    pub fn is_converged(&self) -> bool {
        matches!(self, Termination::Converged)
    }

    /// Whether an observer stopped it (here or in a method it ran).
    pub fn is_stopped(&self) -> bool {
        match self {
            Termination::Stopped { .. } => true,
            Termination::Inner { termination, .. } => termination.is_stopped(),
            _ => false,
        }
    }

    /// This termination seen from an outer method: [`Termination::Converged`] stays converged,
    /// anything else becomes [`Termination::Inner`] of `method`.
    pub fn inside(self, method: Method) -> Termination {
        match self {
            Termination::Converged => Termination::Converged,
            other => Termination::Inner {
                method,
                termination: Box::new(other),
            },
        }
    }
}

impl std::fmt::Display for Termination {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Termination::Converged => write!(f, "converged"),
            Termination::StepLimit {
                steps,
                measure,
                tolerance,
            } => write!(
                f,
                "stopped at its limit of {steps} steps, its measure at {measure:.3e} \
                 (tolerance {tolerance:.1e})"
            ),
            Termination::Stalled { reason } => write!(f, "stalled: {reason}"),
            Termination::NonFinite { field } => write!(
                f,
                "the {field} is not finite: the data overflow f64 (check the load, the \
                 moduli and the units) or the method broke down"
            ),
            Termination::LargeDisplacement {
                displacement_mm,
                size_mm,
            } => write!(
                f,
                "the elastic displacement {displacement_mm:.3e} mm exceeds the size of the \
                 interface {size_mm:.3e} mm: not a small-strain answer (check the moduli, the \
                 load and the units)"
            ),
            Termination::Infeasible { reason } => write!(f, "infeasible: {reason}"),
            Termination::Unbounded { reason } => write!(f, "unbounded: {reason}"),
            Termination::Stopped { after } => {
                write!(f, "stopped by an observer after {after} iterations")
            }
            Termination::Inner {
                method,
                termination,
            } => write!(f, "its {method} {termination}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inner_terminations_read_as_a_sentence() {
        let t = Termination::Stopped { after: 3 }.inside(Method::PolonskyKeer);
        assert!(t.is_stopped() && !t.is_converged());
        assert_eq!(
            t.to_string(),
            "its Polonsky–Keer solve stopped by an observer after 3 iterations"
        );
        assert_eq!(
            Termination::Converged.inside(Method::Qp),
            Termination::Converged
        );
    }
}
