//! The exact one bounce of the headlamp's light with its senders fixed in the world: the
//! reference the GI's flicker is measured against (`headlamp render --view reference`,
//! `headlamp bench --pan`).
//!
//! The GPU reference (`reference_screen`) takes every texel of the lamp's view as a sender, so
//! its senders slide over the walls as the camera turns and the reference itself moves from
//! frame to frame. Here the senders are the level's own triangles cut into patches of at most
//! `max_edge` (2 cm by default): a patch's place depends on the scene alone. Per frame:
//!
//! 1. [`World::lit_patches`]: triangles wholly outside the lamp's frustum or facing away from
//!    it are skipped; the others are cut into n² congruent sub-triangles, and each that has
//!    light on it (inside the frustum, on its lit side, a clear ray from the lamp) reflects
//!    Φ = ρ · I(ω) · max(0, n·l) · A / d², ρ the albedo the G-buffer would give it.
//! 2. [`LitPatches::radiance`]: each receiver (a pixel centre of the frame) gets
//!    L = ρ_r/π · E, E the sum over every lit patch of Φ·cos·cos/(π d²), the patches within a
//!    few patch sizes integrated exactly by their polygon form factor.
//!
//! Everything is CPU code (rayon); the receivers come from the renderer's views.

mod lamp;
mod occlusion;
mod patch;
mod texture;
mod transport;
mod visibility;
mod world;

pub use lamp::Lamp;
pub use patch::{LitPatch, Patch};
pub use transport::{polygon_factor, LitPatches, Receiver, NEAR_EDGES};
pub use visibility::{Cover, Occluders, Seen, VisibilityCube};
pub use world::{subdivisions, World, DEFAULT_MAX_EDGE, SHADOW_OFFSET};
