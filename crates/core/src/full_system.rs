//! The uncondensed system of two bodies in contact (eq. 2.22), as the penalty method on the
//! full system sees it: the bodies' crate builds it, a contact crate solves it, and neither
//! needs the other.

use crate::Result;

/// A joint stiffness system of two bodies with a penalty spring at each contact point, as
/// Kalker's iteration needs it (eq. 2.22):
///
/// (K¹ ⊕ K² + Σ_{i ∈ C} c wᵢ Lᵢᵀ Lᵢ) u = b − Σ_{i ∈ C} c wᵢ hᵢ Lᵢᵀ,
///
/// where Lᵢ u is the closing of the gap at point i, so that dᵢ = hᵢ + Lᵢ u. Springs hold a
/// floating body, so nothing is pinned. An implementation keeps its symbolic factorisation
/// across solves: the pattern holds every candidate spring, and a change of the contact set C
/// costs one numeric refactorisation. `contopt_fem::JointSystem` is one for two finite-element
/// bodies; `contopt_contact::FullPenalty` solves it.
pub trait FullSystem {
    /// Number of contact points n (the candidate springs).
    fn points(&self) -> usize;
    /// Point weights wᵢ \[mm²\] (2πr·ds, b·ds), one per point.
    fn weights(&self) -> &[f64];
    /// The gap hᵢ at zero displacement of the unknowns u: the initial gap plus the share of
    /// prescribed displacements \[mm\], one per point. It sets the scale of round-off in the
    /// gap, and where a floating body touches first.
    fn rest_gap(&self) -> &[f64];
    /// Number of free rigid modes of the bodies: the modes only springs hold.
    fn free_modes(&self) -> usize;
    /// Puts springs of stiffness c·wᵢ at the points of `active` (the contact set C, none
    /// elsewhere), solves the system (2.22) and writes the gaps dᵢ = hᵢ + Lᵢ u of every point
    /// to `gap` \[mm\].
    fn solve_springs(&mut self, active: &[bool], c: f64, gap: &mut [f64]) -> Result<()>;
    /// Amplitudes of the bodies' free rigid modes in the last solve, as the condensed
    /// interface problem reports them (first body's, then the
    /// second's).
    fn rigid(&self) -> Vec<f64>;
    /// The largest equilibrium error of a free rigid mode under `pressure`,
    /// |Σᵢ wᵢ pᵢ rᵢ + q| \[N\] (eq. 2.10).
    fn equilibrium(&self, pressure: &[f64]) -> f64;
}
