//! Cloth let through other cloth for a while.
//!
//! A seam closing over a third layer catches it: GarmentCode hangs a hood's edge over the
//! shoulders and a sleeve's over the side seams, and their cloth lies between the two
//! sides of the seam as they close. Held apart by the self-collision, the seam stalls
//! with the layer pinched in it (rand_1_042: a shoulder 9 mm open with the pull at 1,024
//! times its strength); closed within the weld's tolerance over it, the weld runs through
//! it (rand_1_002: 27 crossings). The sewing finds such layers and lets one side of the
//! seam through them: the other side's contact carries the layer along as the seam
//! closes, and it ends on the far side of the closed seam.

/// The particles of a layer of cloth and those of the cloth let through it: each side is
/// exempt from the other's self-collision until the two have passed through each other
/// (they were seen crossing, then no longer were), or the pass is ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LayerPass {
    pub layer: Vec<usize>,
    pub side: Vec<usize>,
}

/// A layer pass and how it went.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LayerPassing {
    pub pass: LayerPass,
    /// Whether the two sides were seen passing through each other.
    pub crossed: bool,
    /// The step after which it ended (the sides through each other and apart, or the pass
    /// ended by its caller); `None` while it holds.
    pub ended: Option<u64>,
}
