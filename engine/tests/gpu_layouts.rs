//! GPU layouts that cannot drift: every struct of the engine's WGSL, assembled as the engine
//! assembles it (includes expanded), is laid out by naga and compared with its Rust twin
//! (`engine::gpu_layout`), or is one of the GPU-only structs listed there. No GPU needed.

mod layout_check;

use bytemuck::{Pod, Zeroable};
use engine::gpu_layout::{GpuLayout, GPU_ONLY};
use engine::wgpu;
use layout_check::{check, compare, wgsl_structs, WgslStruct};

fn engine_files() -> Vec<(&'static str, String)> {
    engine::passes::SHADERS.iter().map(|(name, source)| (*name, engine::shader::compose(source, &[]))).collect()
}

#[test]
fn every_wgsl_struct_has_its_twins_layout_or_is_gpu_only() {
    let twins = engine::gpu_layout::twins();
    let checked = check(&engine_files(), &twins, GPU_ONLY).unwrap_or_else(|e| panic!("GPU layouts drifted:\n{e}"));
    // Not vacuous: every twin was compared, and every struct seen is a twin or listed.
    assert!(checked.twins > 0 && checked.twins == twins.len(), "compared {} of {} twins", checked.twins, twins.len());
    assert_eq!(checked.structs.len(), twins.len() + GPU_ONLY.len());
}

/// The check reads the passes' sources (`SHADERS`) and what they include: a shader file
/// neither among them nor an include would escape it.
#[test]
fn every_engine_wgsl_file_is_checked() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders");
    let known: Vec<&str> = engine::passes::SHADERS.iter().chain(engine::shader::ENGINE_INCLUDES).map(|f| f.0).collect();
    for entry in std::fs::read_dir(dir).expect("shaders/") {
        let name = entry.expect("an entry").file_name().into_string().expect("a UTF-8 name");
        if name.ends_with(".wgsl") {
            assert!(known.contains(&name.as_str()), "shaders/{name} is neither in passes::SHADERS nor an include");
        }
    }
}

/// The vertex inputs have no memory layout of their own: each `@location` is fed by the
/// attribute of that location in the vertex buffer layout, which must have the member's
/// format, and the attributes must fill the buffer's stride (the Rust vertex struct's size).
#[test]
fn vertex_inputs_match_their_buffer_layouts() {
    let checked = check(&engine_files(), &engine::gpu_layout::twins(), GPU_ONLY).expect("layouts checked above");
    let inputs =
        [("VertexIn", engine::gpu_scene::VERTEX_LAYOUT), ("InstanceIn", engine::gpu_instances::INSTANCE_LAYOUT)];
    for (name, layout) in inputs {
        let input = &checked.structs[name];
        assert_eq!(input.members.len(), layout.attributes.len(), "{name}: one attribute per member");
        for m in &input.members {
            let location = m.location.unwrap_or_else(|| panic!("{name}.{} has no @location", m.name));
            let attribute = layout
                .attributes
                .iter()
                .find(|a| a.shader_location == location)
                .unwrap_or_else(|| panic!("{name}.{}: no attribute at location {location}", m.name));
            assert_eq!(Some(attribute.format), m.vertex_format, "{name}.{} at location {location}", m.name);
        }
        let mut attributes = layout.attributes.to_vec();
        attributes.sort_by_key(|a| a.offset);
        let mut end = 0;
        for a in &attributes {
            assert_eq!(a.offset, end, "{name}: attribute at location {} leaves a gap or overlaps", a.shader_location);
            end += a.format.size();
        }
        assert_eq!(end, layout.array_stride, "{name}: the attributes do not fill the stride");
    }
    // scene::Vertex's fields are VertexIn's members, at their attributes' offsets.
    let vertex_in = &checked.structs["VertexIn"];
    let fields = [
        ("position", std::mem::offset_of!(engine::scene::Vertex, position)),
        ("normal", std::mem::offset_of!(engine::scene::Vertex, normal)),
        ("uv", std::mem::offset_of!(engine::scene::Vertex, uv)),
        ("uv1", std::mem::offset_of!(engine::scene::Vertex, uv1)),
        ("color", std::mem::offset_of!(engine::scene::Vertex, color)),
    ];
    for (field, offset) in fields {
        let location = vertex_in.member(field).location.expect("a location");
        let attribute = engine::gpu_scene::VERTEX_LAYOUT.attributes.iter().find(|a| a.shader_location == location);
        assert_eq!(attribute.map(|a| a.offset), Some(offset as wgpu::BufferAddress), "scene::Vertex::{field}");
    }
}

// The comparison itself, on a twin that has drifted, so the checks above cannot pass vacuously.

const DRIFTED_WGSL: &str = "struct Drifted { a: f32, b: vec4f, c: vec3f, d: u32 };";

fn drifted_wgsl() -> WgslStruct {
    let structs = wgsl_structs("drifted", DRIFTED_WGSL);
    assert_eq!(structs.len(), 1);
    // WGSL aligns `b` to 16 bytes: a at 0, b at 16, c at 32, d at 44; 48 bytes.
    assert_eq!(structs[0].size, 48);
    structs[0].clone()
}

#[test]
fn a_faithful_twin_passes() {
    engine::gpu_struct! {
        #[repr(C)]
        #[derive(Clone, Copy, Pod, Zeroable)]
        struct Twin as Drifted {
            a: f32,
            pad: [f32; 3],
            b: [f32; 4],
            c: [f32; 3],
            d: u32,
        }
    }
    assert_eq!(compare(&drifted_wgsl(), &Twin::layout()), Ok(()));
}

#[test]
fn a_drifted_twin_fails_naming_the_field_and_both_offsets() {
    // The Rust side forgot the alignment of `b`: it lies at 4, not 16, and everything after it
    // moves up.
    engine::gpu_struct! {
        #[repr(C)]
        #[derive(Clone, Copy, Pod, Zeroable)]
        struct Drifted {
            a: f32,
            b: [f32; 4],
            c: [f32; 3],
            d: u32,
            pad: [f32; 3],
        }
    }
    let error = compare(&drifted_wgsl(), &Drifted::layout()).expect_err("b is misplaced");
    assert!(error.contains("Drifted.b: WGSL offset 16 (size 16), Rust offset 4 (size 16)"), "{error}");
    assert!(error.contains("Drifted.c: WGSL offset 32"), "{error}");
    assert!(!error.contains("Drifted.a"), "a is in place: {error}");
}

#[test]
fn a_renamed_or_missing_field_fails() {
    engine::gpu_struct! {
        #[repr(C)]
        #[derive(Clone, Copy, Pod, Zeroable)]
        struct Renamed as Drifted {
            a: f32,
            pad: [f32; 3],
            b: [f32; 4],
            colour: [f32; 3],
            // `d` taken for padding: WGSL has a member there.
            pad_d: u32,
        }
    }
    let error = compare(&drifted_wgsl(), &Renamed::layout()).expect_err("c and d are missing");
    assert!(error.contains("Drifted (Rust Renamed).c: WGSL offset 32 has no Rust field"), "{error}");
    assert!(error.contains("Drifted (Rust Renamed).d: WGSL offset 44 has no Rust field"), "{error}");
    assert!(error.contains("Drifted (Rust Renamed).colour: Rust offset 32 has no WGSL member"), "{error}");
}

#[test]
fn an_unaccounted_struct_and_disagreeing_declarations_fail() {
    let files =
        [("one.wgsl", DRIFTED_WGSL.to_string()), ("two.wgsl", "struct Drifted { a: f32, b: f32 };".to_string())];
    let error = check(&files, &[], &[("Drifted", "test")]).err().expect("the two declarations differ");
    assert!(error.contains("struct Drifted differs between one.wgsl"), "{error}");
    let error = check(&files[..1], &[], &[]).err().expect("Drifted is not accounted for");
    assert!(error.contains("Drifted (one.wgsl) has no Rust twin and is not listed as GPU-only"), "{error}");
    let error = check(&files[..1], &[], &[("Drifted", "test"), ("Gone", "test")]).err().expect("Gone is stale");
    assert!(error.contains("GPU-only Gone: no WGSL file declares it"), "{error}");
}
