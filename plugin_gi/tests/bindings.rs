//! The GI's bind groups, as its Rust declares them (`plugin_gi::bindings()`), against its WGSL
//! as naga reads it, the engine's groups (group 0, `globals`) included: names, kinds, groups
//! and order agree, and every binding is read. No GPU needed.

#[path = "../../engine/tests/binding_check/mod.rs"]
mod binding_check;

#[test]
fn every_gi_bind_group_is_its_wgsl() {
    // The engine's groups that the GI's shaders include (common.wgsl's globals).
    let included = engine::passes::BINDINGS.iter().filter(|g| {
        plugin_gi::SHADERS
            .iter()
            .any(|(_, source)| engine::shader::included(source, plugin_gi::SHADER_INCLUDES).contains(&g.shader))
    });
    let included: Vec<_> = included.copied().collect();
    let problems =
        binding_check::check(plugin_gi::SHADERS, plugin_gi::SHADER_INCLUDES, &plugin_gi::bindings(), &included);
    assert!(problems.is_empty(), "the GI's bind groups and its WGSL disagree:\n{}", problems.join("\n"));
}
