//! Every GI WGSL pass file parses and validates after include expansion (no GPU needed).

#[test]
fn gi_shaders_validate() {
    for (name, source) in plugin_gi::SHADERS {
        let composed = engine::shader::compose(source, plugin_gi::SHADER_INCLUDES);
        let module = naga::front::wgsl::parse_str(&composed)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&composed)));
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&composed)));
    }
}
