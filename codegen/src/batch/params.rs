//! Where a batch kernel's ball parameters and law come from ([`Params`]): per contact in the
//! block's lanes, shared by the whole call as scalars, or, for the rough-ball family, the
//! law per contact too; the inputs the shared mode takes as scalars; and each kernel's name,
//! one per law, variant and mode.

use crate::model::{self, names, Variant};
use std::collections::BTreeSet;

/// Where a batch kernel's ball parameters come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Params {
    /// One set per contact, in the block's lanes.
    PerContact,
    /// One set for the whole batch, passed as scalars (broadcast).
    Shared,
    /// The ball parameters *and the law* of the rough-ball family per contact: each block
    /// carries the lanes of its contacts' laws (`WithLaw { block, law }`), so nothing is
    /// computed once per call. Emitted for the rough and Walton kernels only.
    Each,
}

impl Params {
    /// The two modes every law has, in emission order ([`Params::Each`], the rough family's
    /// third, is emitted with those kernels only).
    pub const ALL: [Params; 2] = [Params::PerContact, Params::Shared];

    /// The batch kernel's function name: `free`, `fixed`, `free_shared`, `fixed_shared`.
    pub fn function_name(self, variant: Variant) -> String {
        match self {
            Params::PerContact => variant.name().to_string(),
            Params::Shared => format!("{}_shared", variant.name()),
            Params::Each => format!("{}_each", variant.name()),
        }
    }

    /// [`Params::function_name`] under `law`: the rough and Walton kernels' names start with
    /// `rough_` and `walton_`.
    pub fn function_name_of(self, law: model::Law, variant: Variant) -> String {
        match law {
            model::Law::Rough => format!("rough_{}", self.function_name(variant)),
            model::Law::Walton => format!("walton_{}", self.function_name(variant)),
            model::Law::NoSlip => self.function_name(variant),
        }
    }
}

/// The ball inputs a variant takes as shared scalars in [`Params::Shared`] mode.
pub(super) fn shared_inputs(variant: Variant) -> BTreeSet<String> {
    let mut set: BTreeSet<String> = [names::radius(1), names::radius(2), names::gamma2(2)]
        .into_iter()
        .collect();
    if variant == Variant::Free {
        set.extend([names::inv_mass(1), names::inv_mass(2), names::gamma2(1)]);
    }
    set
}
