//! What presses a case's bodies together through the contact (`contact.load`).

use serde::{Deserialize, Serialize};

/// What presses the bodies together through the contact.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LoadSpec {
    /// Nothing beyond the bodies' own loads (a finite-element punch's pressure on its top).
    #[default]
    None,
    /// A force \[N\] on the second body, which floats along the contact normal (eq. 2.10).
    ForceN(f64),
    /// The second body pushed in by a given approach \[mm\]: it enters the initial gap, h − δ.
    ApproachMm(f64),
}
