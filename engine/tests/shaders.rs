//! Every core WGSL pass file parses and validates after include expansion (no GPU needed).

#[test]
fn core_shaders_validate() {
    for (name, source) in engine::passes::SHADERS {
        let composed = engine::shader::compose(source, &[]);
        let module = naga::front::wgsl::parse_str(&composed)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&composed)));
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&composed)));
    }
}
