//! The engine's bind groups, as its Rust declares them (`engine::passes::BINDINGS`), against its
//! WGSL as naga reads it: names, kinds, groups and order agree, and every binding is read. No
//! GPU needed.

mod binding_check;

use engine::bindings::{Group, ShaderBinding, WgslGroup};

#[test]
fn every_engine_bind_group_is_its_wgsl() {
    let problems = binding_check::check(engine::passes::SHADERS, &[], engine::passes::BINDINGS, &[]);
    assert!(problems.is_empty(), "the engine's bind groups and its WGSL disagree:\n{}", problems.join("\n"));
}

const SOURCE: &str = "
@group(1) @binding(0) var<uniform> params: vec4f;
@group(1) @binding(1) var normal: texture_2d<f32>;
@group(1) @binding(2) var position: texture_2d<f32>;
@group(1) @binding(3) var<storage, read_write> out: array<vec4f>;

@compute @workgroup_size(1)
fn main() {
    out[0] = params + textureLoad(normal, vec2i(0), 0) + textureLoad(position, vec2i(0), 0);
}
";

const RIGHT: Group = Group::new(
    "sample",
    &[
        ShaderBinding::uniform("params"),
        ShaderBinding::texture("normal"),
        ShaderBinding::texture("position"),
        ShaderBinding::storage_rw("out"),
    ],
);
const SWAPPED: Group = Group::new(
    "sample",
    &[
        ShaderBinding::uniform("params"),
        ShaderBinding::texture("position"),
        ShaderBinding::texture("normal"),
        ShaderBinding::storage_rw("out"),
    ],
);
const WRONG_KIND: Group = Group::new(
    "sample",
    &[
        ShaderBinding::uniform("params"),
        ShaderBinding::texture("normal"),
        ShaderBinding::texture("position"),
        ShaderBinding::storage("out"),
    ],
);
const SHORT: Group = Group::new(
    "sample",
    &[ShaderBinding::uniform("params"), ShaderBinding::texture("normal"), ShaderBinding::texture("position")],
);

fn problems(source: &str, group: u32, layout: &'static Group) -> Vec<String> {
    binding_check::check(&[("sample.wgsl", source)], &[], &[WgslGroup::new("sample.wgsl", group, layout)], &[])
}

#[test]
fn a_name_kind_group_order_or_unread_binding_that_drifts_is_named() {
    assert_eq!(problems(SOURCE, 1, &RIGHT), Vec::<String>::new());
    let swapped = problems(SOURCE, 1, &SWAPPED);
    assert_eq!(swapped.len(), 2, "{swapped:?}");
    assert!(swapped[0].contains("@binding(1): WGSL names it 'normal', sample 'position'"), "{swapped:?}");
    let kind = problems(SOURCE, 1, &WRONG_KIND);
    assert!(kind.len() == 1 && kind[0].contains("'out' is Storage { read_only: false } in WGSL"), "{kind:?}");
    let short = problems(SOURCE, 1, &SHORT);
    assert!(short.len() == 1 && short[0].contains("@binding(3): 'out' is not in sample"), "{short:?}");
    let group = problems(SOURCE, 2, &RIGHT);
    assert!(group.iter().any(|p| p.contains("@group(1) is described by no Rust list")), "{group:?}");
    assert!(group.iter().any(|p| p.contains("describes @group(2), which no shader declares")), "{group:?}");
    let unread = SOURCE.replace(" + textureLoad(position, vec2i(0), 0)", "");
    let unread = problems(&unread, 1, &RIGHT);
    assert!(
        unread.len() == 1 && unread[0].contains("'position' of sample is read by no entry point that uses the group"),
        "{unread:?}"
    );
}
