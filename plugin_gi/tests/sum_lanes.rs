//! The gather's two ways of summing (`SumLanes`) give one picture: the lanes of a subgroup
//! sharing their lights, as lavapipe gets, and each invocation alone, as a device without
//! subgroups of 4 or 8 lanes gets. On lavapipe.

mod common;

use common::*;
use engine::gpu::Gpu;
use engine::wgpu;
use plugin_gi::{GiSettings, SumLanes};

const SIZE: (u32, u32) = (160, 120);

bounds::tolerance! {
    /// The subgroup sum against the invocation sum: block error (the same lights summed in
    /// another order).
    SUMS: at_most 0.0, measured 0.0
}

#[test]
fn the_subgroup_sum_and_the_invocation_sum_give_one_picture() {
    let shared = gpu();
    let alone = Gpu::headless_without(wgpu::Features::SUBGROUP).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(SumLanes::for_device(&alone), SumLanes::Invocation);
    if shared.adapter_name().contains("llvmpipe") {
        let lanes = shared.subgroup_size();
        assert_eq!(SumLanes::for_device(&shared), SumLanes::Subgroup, "lavapipe's subgroups: {lanes:?} lanes");
    }
    // The view takes in the void beside the box (receivers without a surface, which sum with
    // the rest of their subgroup), and the second bounce gathers too; each receiver evaluates
    // every light without the interleave.
    let view = cornell_view(4.0);
    for settings in
        [GiSettings { bounces: 2, ..GiSettings::default() }, GiSettings { interleave: 1, ..GiSettings::default() }]
    {
        let render = |gpu: &Gpu| {
            render_linear(gpu, &mut renderer(gpu, &cornell_box(), settings.clone()), &view, "indirect", SIZE)
        };
        let (a, b) = (render(&shared), render(&alone));
        let total: f64 = a.pixels().map(|p| f64::from(p[0] + p[1] + p[2])).sum();
        bounds::assert(bounds::at_least("the box's indirect light", total, f64::MIN_POSITIVE));
        SUMS.assert(
            format!("{} bounces, interleave {}: the two sums", settings.bounces, settings.interleave),
            block_error(&a, &b),
        );
    }
}
