//! The degree of static indeterminacy of a hinged chain attached to the frame (seed 002,
//! eqs. 1 and 2).
//!
//! Eq. 2 counts directly: every simple hinge carries two unknown force components and every
//! link gives three equations of equilibrium, so n = 2·p1 − 3·m. Eq. 1 counts the closed
//! contours of the structural scheme in which every hinge to the frame is replaced by two
//! hinged support bars (the seed's Fig. 1b, frame counted as one disk): each closed contour
//! of a hinged system has three redundant internal forces, and each simple hinge releases one,
//! so n = 3·σ − p1. For a chain of m links with h_i hinges between links and h_0 hinges to the
//! frame, the scheme has 1 + m + 2·h_0 disks and 4·h_0 + h_i hinges, so
//! σ = 2·h_0 + h_i − m and both formulas give 2·(h_0 + h_i) − 3·m.

/// Eq. 1: n = 3·σ − p1, with σ closed contours and p1 simple hinges of the scheme.
///
/// # Examples
/// The seed's Fig. 1b: σ = 5, p1 = 14, so the group is statically indeterminate once.
/// ```
/// assert_eq!(tmm::kinetostatics::passive::indeterminacy::by_contours(5, 14), 1);
/// ```
#[must_use]
pub fn by_contours(contours: u32, simple_hinges: u32) -> i64 {
    3 * i64::from(contours) - i64::from(simple_hinges)
}

/// Eq. 2: n = 2·p1 − 3·m, with p1 simple hinges (to the frame and between links) and m links.
/// A negative n means the chain moves (−n degrees of freedom, if no part is over-constrained).
///
/// # Examples
/// The group with the parallel coupler (m = 3, p1 = 5) and a plain RRR dyad (m = 2, p1 = 3):
/// ```
/// use tmm::kinetostatics::passive::indeterminacy::by_links;
/// assert_eq!(by_links(5, 3), 1);
/// assert_eq!(by_links(3, 2), 0);
/// ```
#[must_use]
pub fn by_links(simple_hinges: u32, links: u32) -> i64 {
    2 * i64::from(simple_hinges) - 3 * i64::from(links)
}

/// The number of independent closed contours of a connected system of `disks` rigid disks
/// joined by `hinges` simple hinges: σ = hinges − disks + 1 (the cyclomatic number of its
/// graph). `None` if there are too few hinges to connect the disks (or no disk at all with
/// `u32::MAX` hinges, when σ does not fit in a `u32`).
#[must_use]
pub fn contours(hinges: u32, disks: u32) -> Option<u32> {
    // In u64, so that `hinges + 1` cannot overflow.
    (u64::from(hinges) + 1)
        .checked_sub(u64::from(disks))
        .and_then(|sigma| u32::try_from(sigma).ok())
}

/// A chain of links joined by simple hinges, some of them to the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HingedChain {
    /// Number of moving links, m.
    pub links: u32,
    /// Hinges between two moving links.
    pub inner_hinges: u32,
    /// Hinges of a moving link to the frame.
    pub frame_hinges: u32,
}

/// The structural scheme of eq. 1: every hinge to the frame replaced by two support bars.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SupportBarScheme {
    /// Rigid disks: the frame, the links and the support bars.
    pub disks: u32,
    /// Simple hinges: two at the ends of every support bar, plus the inner hinges.
    pub hinges: u32,
}

impl HingedChain {
    /// The seed's group: links AB, CD, B–D–E; inner hinges B, D; frame hinges A, C, E.
    pub const PARALLEL_COUPLER: HingedChain = HingedChain {
        links: 3,
        inner_hinges: 2,
        frame_hinges: 3,
    };

    /// p1 of eq. 2: all simple hinges of the chain (saturating at `u32::MAX`, far beyond any
    /// real chain; [`HingedChain::by_links`] counts exactly).
    #[must_use]
    pub fn simple_hinges(&self) -> u32 {
        self.inner_hinges.saturating_add(self.frame_hinges)
    }

    /// The scheme of the seed's Fig. 1b (each count saturating at `u32::MAX`, far beyond any
    /// real chain; [`HingedChain::by_contours`] counts exactly).
    #[must_use]
    pub fn support_bar_scheme(&self) -> SupportBarScheme {
        let (disks, hinges) = self.scheme_counts();
        SupportBarScheme {
            disks: u32::try_from(disks).unwrap_or(u32::MAX),
            hinges: u32::try_from(hinges).unwrap_or(u32::MAX),
        }
    }

    /// The disks and hinges of the support-bar scheme, in i64 (no overflow for any u32 input).
    fn scheme_counts(&self) -> (i64, i64) {
        let (m, h0, hi) = (
            i64::from(self.links),
            i64::from(self.frame_hinges),
            i64::from(self.inner_hinges),
        );
        (1 + m + 2 * h0, 4 * h0 + hi)
    }

    /// n by eq. 2.
    #[must_use]
    pub fn by_links(&self) -> i64 {
        2 * (i64::from(self.inner_hinges) + i64::from(self.frame_hinges))
            - 3 * i64::from(self.links)
    }

    /// n by eq. 1, on the support-bar scheme; `None` if that scheme is not connected.
    ///
    /// # Examples
    /// ```
    /// use tmm::kinetostatics::passive::indeterminacy::HingedChain;
    /// let g = HingedChain::PARALLEL_COUPLER;
    /// let scheme = g.support_bar_scheme();
    /// assert_eq!((scheme.disks, scheme.hinges), (10, 14));
    /// assert_eq!(g.by_contours(), Some(1));
    /// assert_eq!(g.by_links(), 1);
    /// ```
    #[must_use]
    pub fn by_contours(&self) -> Option<i64> {
        let (disks, hinges) = self.scheme_counts();
        let sigma = hinges - disks + 1;
        (sigma >= 0).then(|| 3 * sigma - hinges)
    }
}
