//! The numbers the GI's Rust and WGSL both count with (see `engine::shared_constants`):
//! plugin_gi/tests/shared_constants.rs reads the WGSL with naga and compares each with its
//! Rust constant.

use engine::shared_constants::{SharedConstant, Workgroup};
use engine::{shared_constant, workgroup};

use crate::cuts_layout::{CUTS_GROUP, TILE};
use crate::passes::GROUP_SIDE;
use crate::pipelines::TEXEL_GROUP;

/// WGSL constants with the value of a Rust constant.
pub const CONSTANTS: &[SharedConstant] = &[
    shared_constant!("gi_common.wgsl", PYRAMID_LEVELS = crate::quadtree::LEVELS),
    shared_constant!("gi_common.wgsl", CUT_TILE = crate::cuts_layout::TILE),
    shared_constant!("gi_common.wgsl", CUT_MAX = crate::cuts_layout::CUT_MAX),
    shared_constant!("gi_common.wgsl", RECEIVER_PERIOD = crate::grids::RECEIVER_PERIOD),
    shared_constant!("gi_common.wgsl", SENDER_PAD = crate::grids::SENDER_PAD),
    shared_constant!("gi_common.wgsl", SENDER_STEPS_OFFSET = crate::grids::SENDER_STEPS_OFFSET),
    shared_constant!("world_sight.wgsl", WORLD_BLOCK = occupancy::BLOCK),
    shared_constant!("world_sight.wgsl", WORLD_MAX_STEPS = occupancy::MAX_STEPS),
    shared_constant!("pyramid.wgsl", GROUP_LEVELS = crate::passes::GROUP_LEVELS),
    shared_constant!("gi/cuts.wgsl", CUTS_GROUP = crate::cuts_layout::CUTS_GROUP),
    shared_constant!("gi/article_stream.wgsl", LIGHTS_PER_SLOT = crate::passes::LIGHTS_PER_SLOT),
    shared_constant!("gi/article_stream.wgsl", ENTRY_COARSE = crate::distribution_table::ENTRY_COARSE),
    shared_constant!("gi/article_stream.wgsl", ENTRY_FINE = crate::distribution_table::ENTRY_FINE),
];

/// Entry points whose workgroup size the Rust dispatches count with.
pub const WORKGROUPS: &[Workgroup] = &[
    workgroup!("gi/pyramid_lamp.wgsl", "flux_levels", [GROUP_SIDE, GROUP_SIDE, 1]),
    workgroup!("gi/pyramid_lamp.wgsl", "reduce", [GROUP_SIDE, GROUP_SIDE, 1]),
    workgroup!("gi/pyramid_bounce.wgsl", "flux_levels", [GROUP_SIDE, GROUP_SIDE, 1]),
    workgroup!("gi/pyramid_bounce.wgsl", "reduce", [GROUP_SIDE, GROUP_SIDE, 1]),
    // One invocation a tile.
    workgroup!("gi/cuts.wgsl", "main", [CUTS_GROUP, 1, 1]),
    workgroup!("gi/cuts.wgsl", "retry_full_tiles", [CUTS_GROUP, 1, 1]),
    // One workgroup a tile, one invocation a receiver.
    workgroup!("gi/gather_subgroup.wgsl", "main", [TILE * TILE, 1, 1]),
    workgroup!("gi/gather_subgroup.wgsl", "main_bounce", [TILE * TILE, 1, 1]),
    workgroup!("gi/gather_invocation.wgsl", "main", [TILE * TILE, 1, 1]),
    workgroup!("gi/gather_invocation.wgsl", "main_bounce", [TILE * TILE, 1, 1]),
    workgroup!("gi/sight.wgsl", "main", [TILE * TILE, 1, 1]),
    workgroup!("gi/sight_depth.wgsl", "main", [TEXEL_GROUP, TEXEL_GROUP, 1]),
    workgroup!("gi/temporal.wgsl", "main", [TEXEL_GROUP, TEXEL_GROUP, 1]),
    workgroup!("gi/article_sub_images.wgsl", "split", [TEXEL_GROUP, TEXEL_GROUP, 1]),
    workgroup!("gi/article_sub_images.wgsl", "join", [TEXEL_GROUP, TEXEL_GROUP, 1]),
    workgroup!("gi/reference.wgsl", "main", [crate::passes::REFERENCE_GROUP, 1, 1]),
];
