//! Typed handles of a plan's joints, links and named points, and the one conversion by which
//! a name or a handle names one: resolve a name once ([`Plan::joint_id`](super::Plan::joint_id))
//! and read by handle in a loop, with no string look-up per number.

use crate::error::{Error, Result};
use std::fmt;

/// Checks index `i` (called `name`, for example `"joint index"`) against a collection of `len`
/// `things`: `Ok(i)` below `len`, else [`Error::OutOfRange`] over `[0, len − 1]`, or
/// [`Error::Description`] when there are no `things` at all (no interval to name).
pub(crate) fn index_in(name: &'static str, things: &str, i: usize, len: usize) -> Result<usize> {
    if i < len {
        Ok(i)
    } else if len == 0 {
        Err(Error::Description {
            item: format!("{name} {i}"),
            problem: format!("the linkage has no {things}"),
        })
    } else {
        Err(Error::OutOfRange {
            name,
            value: i as f64,
            min: 0.0,
            max: (len - 1) as f64,
            ends: crate::Ends::Closed,
        })
    }
}

macro_rules! handle {
    (
        $(#[$doc:meta])* $id:ident, $reference:ident, $method:ident,
        $what:literal, $index:literal, $things:literal, $not:literal
    ) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
        pub struct $id(pub(crate) usize);

        impl $id {
            /// Its index in the plan's list of names.
            #[must_use]
            pub fn index(self) -> usize {
                self.0
            }
        }

        impl From<$id> for usize {
            fn from(id: $id) -> usize {
                id.0
            }
        }

        impl fmt::Display for $id {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, concat!($what, " #{}"), self.0)
            }
        }

        #[doc = concat!(
            "Something that names a ", $what, " of a plan: its name (`&str`, `String`), its ",
            "handle [`", stringify!($id), "`], or its index (`usize`). Every reading that takes a ",
            $what, " takes one of these: a name is looked up, a handle or an index only checked ",
            "against the plan."
        )]
        pub trait $reference {
            #[doc = concat!(
                "The handle of the ", $what, " among `names` (the plan's ", $things, ", in order)."
            )]
            ///
            /// # Errors
            #[doc = concat!(
                "[`Error::Description`] for an unknown name; [`Error::OutOfRange`] (`\"",
                $index, "\"`) for a handle beyond the plan's (one of another plan)."
            )]
            fn $method(&self, names: &[String]) -> Result<$id>;
        }

        impl $reference for $id {
            #[inline]
            fn $method(&self, names: &[String]) -> Result<$id> {
                index_in($index, $things, self.0, names.len()).map($id)
            }
        }

        /// An index into the plan's names (what [`index`]($id::index) gives), checked.
        impl $reference for usize {
            #[inline]
            fn $method(&self, names: &[String]) -> Result<$id> {
                index_in($index, $things, *self, names.len()).map($id)
            }
        }

        impl $reference for str {
            fn $method(&self, names: &[String]) -> Result<$id> {
                names
                    .iter()
                    .position(|n| n == self)
                    .map($id)
                    .ok_or_else(|| Error::Description {
                        item: format!(concat!($what, " {}"), self),
                        problem: $not.to_owned(),
                    })
            }
        }

        impl $reference for String {
            fn $method(&self, names: &[String]) -> Result<$id> {
                self.as_str().$method(names)
            }
        }

        impl<T: $reference + ?Sized> $reference for &T {
            #[inline]
            fn $method(&self, names: &[String]) -> Result<$id> {
                (**self).$method(names)
            }
        }
    };
}

handle!(
    /// A joint of a plan, by its index in [`Plan::joint_names`](super::Plan::joint_names).
    JointId, JointRef, joint_in, "joint", "joint index", "joints",
    "is not a joint of this linkage"
);
handle!(
    /// A link of a plan, by its index in [`Plan::link_names`](super::Plan::link_names)
    /// (0 is the frame).
    LinkId, LinkRef, link_in, "link", "link index", "links",
    "is not a link of this linkage"
);
handle!(
    /// A named point of a plan, by its index in
    /// [`Plan::point_names`](super::Plan::point_names).
    PointId, PointRef, point_in, "point", "point index", "named points",
    "is not a named point of this linkage"
);

impl LinkId {
    /// The frame (link 0).
    pub const FRAME: Self = Self(0);
}
