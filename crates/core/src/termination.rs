//! How an iterative method ended: one answer for every contact solver, optimisation and search
//! (argmin's `TerminationReason`, clarabel's `SolverStatus`). A method that stops short is not
//! an error: it returns its last iterate with a [`Termination`] that says why and how far it
//! got; errors are for bad input and for work refused before it starts.
//!
//! Every cause is typed, as clarabel's statuses and faer's `LltError::NonPositivePivot
//! { index }` are: a [`Stall`] says which system failed and where, a [`Quantity`] which value
//! is not finite, an [`Infeasibility`] which bound or constraints conflict, with the point and
//! by how much. `Display` writes each as a sentence.

use serde::{Deserialize, Serialize};

use crate::observe::Method;

/// Why a method stopped.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Termination {
    /// The method met its tolerance.
    Converged,
    /// The method met only a reduced tolerance (clarabel's `AlmostSolved`): its answer
    /// stands, as a solution of lesser accuracy, and says so.
    ReducedAccuracy {
        /// The convergence measure it reached.
        measure: f64,
        /// The value it had to reach.
        tolerance: f64,
    },
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
    /// contact set that kept cycling.
    Stalled {
        /// Which.
        cause: Stall,
    },
    /// A value became NaN or infinite: the data overflow f64 or the method broke down.
    NonFinite {
        /// The quantity that is not finite.
        quantity: Quantity,
    },
    /// The elastic displacement exceeds the size of the interface: no small-strain answer
    /// (the moduli, the load or the units are off).
    LargeDisplacement {
        /// The largest elastic displacement \[mm\].
        displacement_mm: f64,
        /// The size of the interface \[mm\].
        size_mm: f64,
    },
    /// The programme has no feasible point, or its optimum breaks a bound it must keep.
    Infeasible {
        /// Which constraints conflict, where.
        cause: Infeasibility,
    },
    /// The programme's objective is unbounded.
    Unbounded {
        /// What leaves it free.
        cause: Unboundedness,
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

/// Why a method could not make progress.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Stall {
    /// The influence matrix (with the penalty term ρ on its diagonal) has no Cholesky factor
    /// on the contact set: Kalker's solve (2.10) on C is singular.
    SingularOnContactSet {
        /// Points in the contact set.
        points: usize,
        /// The penalty term ρ on the diagonal.
        rho: f64,
    },
    /// The contact points cannot hold the rigid modes: Rᵀ W on C (2.10) is rank-deficient.
    RigidModesUnheld {
        /// Points in the contact set.
        points: usize,
    },
    /// The influence operator is not positive along a conjugate direction on the contact set.
    NotPositive {
        /// The curvature tᵀ A t found.
        curvature: f64,
    },
    /// clarabel's interior point ended short of its tolerance without an answer.
    InteriorPoint {
        /// clarabel's status.
        status: InteriorPointStatus,
        /// Its primal residual.
        primal_residual: f64,
        /// Its dual residual.
        dual_residual: f64,
    },
    /// The exact solve on the interior point's contact set disagrees with it in a rigid
    /// amplitude.
    PolishDisagrees {
        /// The rigid mode.
        mode: usize,
        /// The polished amplitude.
        polished: f64,
        /// The interior point's.
        interior_point: f64,
    },
    /// The contact sets of the passes of a restricted programme came back to one tried
    /// before.
    CyclingContactSet {
        /// Passes done.
        passes: usize,
        /// The constraints the last pass's programme could not meet together.
        conflict: Infeasibility,
    },
    /// The node of least gap change kept moving between programmes.
    WanderingReference {
        /// Programmes solved.
        moves: usize,
    },
    /// A line search found no decrease of the potential it minimises.
    NoDescent {
        /// The imbalance (gradient) at which it stopped.
        imbalance: f64,
    },
}

/// clarabel's statuses that leave no answer, short of the iteration limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum InteriorPointStatus {
    /// Not solved at all.
    Unsolved,
    /// Its time limit.
    TimeLimit,
    /// A numerical error (a factorisation that failed).
    NumericalError,
    /// Progress too slow to go on.
    InsufficientProgress,
    /// Its callback stopped it.
    CallbackTerminated,
}

/// A quantity that is not finite.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Quantity {
    /// The contact pressure p.
    Pressure,
    /// The gap d.
    Gap,
    /// A rigid-body amplitude λ.
    RigidAmplitude,
    /// A residual of the solution.
    Residual,
    /// The potential or the imbalance of a bearing's rings.
    RingEquilibrium,
    /// A figure of a case's report, by its name.
    Figure {
        /// The figure.
        name: String,
    },
}

/// Why a programme has no feasible point, or its optimum breaks a bound.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Infeasibility {
    /// p passes v·p_max on Ω_nv (χ ≥ 0 of 3.4): the gap change there follows its design
    /// column, which Ω_v closes at v·p_max, so no gap change keeps it.
    OmegaNv {
        /// The point.
        point: usize,
        /// Where it is \[mm\].
        position_mm: [f64; 3],
        /// p − v·p_max there \[MPa\].
        excess_mpa: f64,
        /// The load case (from 1) of an envelope; `None` for the design case.
        case: Option<usize>,
    },
    /// p passes v·p_max on Ω_v, where the design prescribes p = v·p_max: the gap change
    /// fitted there (step 6) cannot hold it.
    OmegaVNotHeld {
        /// The point.
        point: usize,
        /// Where it is \[mm\].
        position_mm: [f64; 3],
        /// p − v·p_max there \[MPa\].
        excess_mpa: f64,
    },
    /// The constraints of the linear programme (3.5) that conflict, as its infeasibility
    /// certificate names them, the most to blame first.
    Programme {
        /// The first few.
        conflict: Vec<Constraint>,
        /// How many more.
        more: usize,
    },
}

/// A constraint of the linear programme (3.5).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Constraint {
    /// The equilibrium Rᵀ W p = −q of a rigid mode under its load.
    Equilibrium {
        /// The mode's name.
        mode: String,
    },
    /// d ≥ 0 at a point.
    Gap {
        /// The point.
        point: usize,
        /// Where it is \[mm\].
        position_mm: [f64; 3],
    },
    /// p ≤ v·p_max (χ ≥ 0) at a point of Ω_nv.
    Chi {
        /// The point.
        point: usize,
        /// Where it is \[mm\].
        position_mm: [f64; 3],
    },
    /// p ≥ 0 at a point.
    Pressure {
        /// The point.
        point: usize,
        /// Where it is \[mm\].
        position_mm: [f64; 3],
    },
    /// p_max ≥ 0.
    Level,
    /// Δh ≥ 0 at a design node.
    Change {
        /// The node.
        node: usize,
        /// Where it is \[mm\].
        position_mm: [f64; 3],
    },
}

/// What leaves a programme's objective free.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum Unboundedness {
    /// p_max falls without bound along a gap change that nothing in the programme limits.
    GapChange,
}

impl Termination {
    /// Whether the method met its tolerance.
    pub fn is_converged(&self) -> bool {
        matches!(self, Termination::Converged)
    }

    /// Whether its answer stands: it converged, or met a reduced tolerance only (here or in a
    /// method it ran; clarabel's `Solved` and `AlmostSolved` alike). An outer method goes on
    /// from such an answer and ends saying the reduced accuracy.
    pub fn is_solved(&self) -> bool {
        match self {
            Termination::Converged | Termination::ReducedAccuracy { .. } => true,
            Termination::Inner { termination, .. } => termination.is_solved(),
            _ => false,
        }
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

    /// How a method ends that would end as `self` after running inner methods, the first of
    /// whose answers of reduced accuracy is `reduced`: a convergence becomes that reduced
    /// accuracy; any other end stays.
    pub fn with_reduced(self, reduced: Option<Termination>) -> Termination {
        match (self, reduced) {
            (Termination::Converged, Some(reduced)) => reduced,
            (end, _) => end,
        }
    }
}

impl std::fmt::Display for Termination {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Termination::Converged => write!(f, "converged"),
            Termination::ReducedAccuracy { measure, tolerance } => write!(
                f,
                "solved to a reduced accuracy only, its measure at {measure:.3e} (tolerance \
                 {tolerance:.1e})"
            ),
            Termination::StepLimit {
                steps,
                measure,
                tolerance,
            } => write!(
                f,
                "stopped at its limit of {steps} steps, its measure at {measure:.3e} \
                 (tolerance {tolerance:.1e})"
            ),
            Termination::Stalled { cause } => write!(f, "stalled: {cause}"),
            Termination::NonFinite { quantity } => write!(
                f,
                "the {quantity} is not finite: the data overflow f64 (check the load, the \
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
            Termination::Infeasible { cause } => write!(f, "infeasible: {cause}"),
            Termination::Unbounded { cause } => write!(f, "unbounded: {cause}"),
            Termination::Stopped { after } => {
                write!(f, "stopped by an observer after {after} iterations")
            }
            Termination::Inner {
                method,
                termination,
            } => write!(f, "in its {method}: {termination}"),
        }
    }
}

impl std::fmt::Display for Stall {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stall::SingularOnContactSet { points, rho } => write!(
                f,
                "the influence matrix is singular on the {points} contact points (penalty term \
                 rho = {rho:e}); use a finite penalty parameter or the augmented Lagrangian"
            ),
            Stall::RigidModesUnheld { points } => {
                write!(f, "the {points} contact points do not hold the rigid modes")
            }
            Stall::NotPositive { curvature } => write!(
                f,
                "the influence operator is not positive on the contact set (curvature \
                 {curvature:e})"
            ),
            Stall::InteriorPoint {
                status,
                primal_residual,
                dual_residual,
            } => write!(
                f,
                "clarabel status {status:?}, primal residual {primal_residual:.3e}, dual \
                 residual {dual_residual:.3e}"
            ),
            Stall::PolishDisagrees {
                mode,
                polished,
                interior_point,
            } => write!(
                f,
                "polished rigid amplitude {mode} = {polished:e} disagrees with the interior \
                 point's {interior_point:e}"
            ),
            Stall::CyclingContactSet { passes, conflict } => write!(
                f,
                "the contact sets of its passes repeat after {passes} passes ({conflict})"
            ),
            Stall::WanderingReference { moves } => write!(
                f,
                "the node of least gap change moved {moves} times between programmes"
            ),
            Stall::NoDescent { imbalance } => write!(
                f,
                "the line search found no decrease of the rings' potential at an imbalance of \
                 {imbalance:e}"
            ),
        }
    }
}

impl std::fmt::Display for Quantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Quantity::Pressure => write!(f, "pressure"),
            Quantity::Gap => write!(f, "gap"),
            Quantity::RigidAmplitude => write!(f, "rigid amplitude"),
            Quantity::Residual => write!(f, "residual"),
            Quantity::RingEquilibrium => write!(f, "rings' equilibrium"),
            Quantity::Figure { name } => write!(f, "{name}"),
        }
    }
}

impl Infeasibility {
    /// Whether it breaks χ ≥ 0 on Ω_nv (3.4): p above v·p_max there, or a conflict that
    /// names that bound.
    pub fn on_omega_nv(&self) -> bool {
        match self {
            Infeasibility::OmegaNv { .. } => true,
            Infeasibility::OmegaVNotHeld { .. } => false,
            Infeasibility::Programme { conflict, .. } => {
                conflict.iter().any(|c| matches!(c, Constraint::Chi { .. }))
            }
        }
    }
}

impl std::fmt::Display for Infeasibility {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Infeasibility::OmegaNv {
                point,
                position_mm,
                excess_mpa,
                case,
            } => {
                if let Some(case) = case {
                    write!(f, "in case {case}: ")?;
                }
                write!(
                    f,
                    "p passes v·p_max by {excess_mpa:.4e} MPa at point {point} {position_mm:?} of Ω_nv \
                     (χ ≥ 0 of 3.4): the gap change there follows its design column, which Ω_v \
                     closes at v·p_max, so no gap change keeps it; the linear programme (3.5) \
                     finds the same. Put Ω_v where each column's pressure peaks"
                )
            }
            Infeasibility::OmegaVNotHeld {
                point,
                position_mm,
                excess_mpa,
            } => write!(
                f,
                "p passes v·p_max by {excess_mpa:.4e} MPa at point {point} {position_mm:?} of Ω_v, \
                 where the design prescribes p = v·p_max: the gap change fitted there (step 6) \
                 cannot hold it, as where a face beyond Ω_v's edge touches; move Ω_v's edge or \
                 coarsen the faces there"
            ),
            Infeasibility::Programme { conflict, more } => {
                write!(f, "no gap change meets these together: ")?;
                for (k, c) in conflict.iter().enumerate() {
                    let sep = if k == 0 { "" } else { "; " };
                    write!(f, "{sep}{c}")?;
                }
                match more {
                    0 => Ok(()),
                    more => write!(f, " and {more} more"),
                }
            }
        }
    }
}

impl std::fmt::Display for Constraint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Constraint::Equilibrium { mode } => {
                write!(f, "the equilibrium of {mode} under its load")
            }
            Constraint::Gap { point, position_mm } => {
                write!(f, "d ≥ 0 at point {point} {position_mm:?}")
            }
            Constraint::Chi { point, position_mm } => {
                write!(
                    f,
                    "p ≤ v·p_max (χ ≥ 0) at point {point} {position_mm:?} of Ω_nv"
                )
            }
            Constraint::Pressure { point, position_mm } => {
                write!(f, "p ≥ 0 at point {point} {position_mm:?}")
            }
            Constraint::Level => write!(f, "p_max ≥ 0"),
            Constraint::Change { node, position_mm } => {
                write!(f, "Δh ≥ 0 at design node {node} {position_mm:?}")
            }
        }
    }
}

impl std::fmt::Display for Unboundedness {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Unboundedness::GapChange => write!(
                f,
                "p_max falls without bound along a gap change that nothing in the programme \
                 limits"
            ),
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
            "in its Polonsky–Keer solve: stopped by an observer after 3 iterations"
        );
        assert_eq!(
            Termination::Converged.inside(Method::Qp),
            Termination::Converged
        );
    }

    /// A reduced accuracy is solved but not converged, inside an outer method too, and an
    /// outer convergence takes it on.
    #[test]
    fn reduced_accuracy_is_solved_not_converged() {
        let reduced = Termination::ReducedAccuracy {
            measure: 1e-6,
            tolerance: 1e-10,
        }
        .inside(Method::Qp);
        assert!(reduced.is_solved() && !reduced.is_converged());
        let outer = Termination::Converged.with_reduced(Some(reduced.clone()));
        assert_eq!(outer, reduced);
        let limit = Termination::Stopped { after: 1 };
        assert_eq!(limit.clone().with_reduced(Some(reduced)), limit);
        assert!(!limit.is_solved());
    }

    /// The causes name their point and figure, and tell Ω_nv apart.
    #[test]
    fn causes_say_where() {
        let chi = Constraint::Chi {
            point: 4,
            position_mm: [1.0, 0.0, 0.0],
        };
        let conflict = Infeasibility::Programme {
            conflict: vec![Constraint::Level, chi],
            more: 2,
        };
        assert!(conflict.on_omega_nv());
        assert_eq!(
            conflict.to_string(),
            "no gap change meets these together: p_max ≥ 0; p ≤ v·p_max (χ ≥ 0) at point 4 \
             [1.0, 0.0, 0.0] of Ω_nv and 2 more"
        );
        let held = Infeasibility::OmegaVNotHeld {
            point: 1,
            position_mm: [0.0; 3],
            excess_mpa: 2.0,
        };
        assert!(!held.on_omega_nv());
        let stall = Termination::Stalled {
            cause: Stall::SingularOnContactSet {
                points: 3,
                rho: 0.0,
            },
        };
        assert!(stall
            .to_string()
            .contains("singular on the 3 contact points"));
    }
}
