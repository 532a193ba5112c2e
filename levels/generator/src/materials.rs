//! The shipped levels' materials: a base colour each (the glTF base colour factor), for the
//! textured ones a procedural base colour texture that multiplies it, and how they reflect the
//! lamp (glTF's metallic and roughness factors, and a roughness texture for wet floors).

use crate::textures::TextureKind;

/// Every material of every level. The declaration order is the order meshes and materials appear
/// in a level's glTF (only the materials a level uses are written, so adding one at the end
/// leaves the other levels' files unchanged).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Material {
    White,
    Red,
    Green,
    Blue,
    Yellow,
    Concrete,
    Wood,
    /// White plaster (the gallery's white rooms).
    Plaster,
    RedPlaster,
    BluePlaster,
    GreenTile,
    YellowBrick,
    /// Light grey floor tiles.
    FloorTile,
    /// Wooden floorboards.
    Planks,
    /// Grey flagstones (the hall's floor, its pillars).
    Stone,
    /// Terracotta brick (the hall's walls).
    Brick,
    /// Dark wooden boards (the hall's ceiling, its balconies).
    DarkPlanks,
    /// The cellar's off-white painted plaster, a satin paint.
    CellarPlaster,
    /// Green painted plaster (the cellar's red/green room).
    GreenPlaster,
    /// Cast concrete with pores and stains (the cellar's floors).
    CellarConcrete,
    /// Dark flagstones with puddles that glint in the beam (the cellar's hall floor).
    WetStone,
    /// Varnished wooden boards (the cellar's crates).
    VarnishedWood,
    /// Galvanised steel (pipes, the way out's door): a metal.
    Steel,
    /// Copper pipe: a coloured metal.
    Copper,
}

impl Material {
    pub const ALL: [Material; 24] = [
        Material::White,
        Material::Red,
        Material::Green,
        Material::Blue,
        Material::Yellow,
        Material::Concrete,
        Material::Wood,
        Material::Plaster,
        Material::RedPlaster,
        Material::BluePlaster,
        Material::GreenTile,
        Material::YellowBrick,
        Material::FloorTile,
        Material::Planks,
        Material::Stone,
        Material::Brick,
        Material::DarkPlanks,
        Material::CellarPlaster,
        Material::GreenPlaster,
        Material::CellarConcrete,
        Material::WetStone,
        Material::VarnishedWood,
        Material::Steel,
        Material::Copper,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Material::White => "white",
            Material::Red => "red",
            Material::Green => "green",
            Material::Blue => "blue",
            Material::Yellow => "yellow",
            Material::Concrete => "concrete",
            Material::Wood => "wood",
            Material::Plaster => "plaster",
            Material::RedPlaster => "red_plaster",
            Material::BluePlaster => "blue_plaster",
            Material::GreenTile => "green_tile",
            Material::YellowBrick => "yellow_brick",
            Material::FloorTile => "floor_tile",
            Material::Planks => "planks",
            Material::Stone => "stone",
            Material::Brick => "brick",
            Material::DarkPlanks => "dark_planks",
            Material::CellarPlaster => "cellar_plaster",
            Material::GreenPlaster => "green_plaster",
            Material::CellarConcrete => "cellar_concrete",
            Material::WetStone => "wet_stone",
            Material::VarnishedWood => "varnished_wood",
            Material::Steel => "steel",
            Material::Copper => "copper",
        }
    }

    /// Linear base colour factor: the diffuse albedo of a dielectric, kept at or below 0.85 so
    /// multi-bounce GI stays well behaved (a texture, values at most 1, only darkens it); a
    /// metal's specular colour (F0), which has no diffuse albedo at all.
    pub fn albedo(self) -> [f64; 3] {
        match self {
            Material::White => [0.8, 0.8, 0.8],
            Material::Red => [0.8, 0.1, 0.08],
            Material::Green => [0.1, 0.7, 0.15],
            Material::Blue => [0.1, 0.2, 0.8],
            Material::Yellow => [0.85, 0.75, 0.1],
            Material::Concrete => [0.45, 0.45, 0.45],
            Material::Wood => [0.55, 0.35, 0.18],
            Material::Plaster => [0.82, 0.8, 0.76],
            Material::RedPlaster => [0.85, 0.07, 0.05],
            Material::BluePlaster => [0.06, 0.16, 0.85],
            Material::GreenTile => [0.08, 0.72, 0.14],
            Material::YellowBrick => [0.85, 0.7, 0.06],
            Material::FloorTile => [0.74, 0.74, 0.72],
            Material::Planks => [0.62, 0.42, 0.24],
            Material::Stone => [0.58, 0.56, 0.52],
            Material::Brick => [0.66, 0.32, 0.2],
            Material::DarkPlanks => [0.34, 0.22, 0.13],
            Material::CellarPlaster => [0.78, 0.76, 0.7],
            Material::GreenPlaster => [0.07, 0.68, 0.1],
            Material::CellarConcrete => [0.5, 0.49, 0.46],
            Material::WetStone => [0.36, 0.35, 0.33],
            Material::VarnishedWood => [0.6, 0.36, 0.16],
            // Measured F0 of zinc-coated steel and of copper (linear).
            Material::Steel => [0.62, 0.63, 0.64],
            Material::Copper => [0.95, 0.64, 0.54],
        }
    }

    /// glTF's metallicFactor: 1 for metals, 0 for everything else.
    pub fn metallic(self) -> f64 {
        match self {
            Material::Steel | Material::Copper => 1.0,
            _ => 0.0,
        }
    }

    /// glTF's roughnessFactor (perceptual roughness; multiplied by [`Self::roughness_texture`]
    /// where there is one). 1 is matte: the older levels' materials keep it.
    pub fn roughness(self) -> f64 {
        match self {
            Material::CellarPlaster | Material::GreenPlaster => 0.6,
            Material::CellarConcrete => 0.85,
            Material::WetStone => 1.0,
            Material::VarnishedWood => 0.35,
            Material::Steel => 0.3,
            Material::Copper => 0.25,
            _ => 1.0,
        }
    }

    /// A greyscale metallic-roughness texture (its green channel scales the roughness; its blue
    /// channel, the same grey, scales a metallic factor of 0 and so changes nothing), sharing
    /// the base colour texture's coordinates.
    pub fn roughness_texture(self) -> Option<TextureKind> {
        match self {
            Material::WetStone => Some(TextureKind::Puddles),
            _ => None,
        }
    }

    /// The base colour texture and how many metres one repeat of it covers (texture
    /// coordinates are world metres divided by this; a power of two, so the division is exact).
    pub fn texture(self) -> Option<(TextureKind, f64)> {
        match self {
            Material::White
            | Material::Red
            | Material::Green
            | Material::Blue
            | Material::Yellow
            | Material::Concrete
            | Material::Wood => None,
            Material::Plaster | Material::RedPlaster | Material::BluePlaster => Some((TextureKind::Plaster, 2.0)),
            Material::GreenTile | Material::FloorTile => Some((TextureKind::Tiles, 1.0)),
            Material::YellowBrick | Material::Brick => Some((TextureKind::Brick, 1.0)),
            Material::Planks | Material::DarkPlanks => Some((TextureKind::Planks, 2.0)),
            Material::Stone | Material::WetStone => Some((TextureKind::Stone, 2.0)),
            Material::CellarPlaster | Material::GreenPlaster => Some((TextureKind::Plaster, 2.0)),
            Material::CellarConcrete => Some((TextureKind::Concrete, 2.0)),
            Material::VarnishedWood => Some((TextureKind::Planks, 2.0)),
            Material::Steel | Material::Copper => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn albedos_are_below_085_and_metals_are_below_1() {
        for m in Material::ALL {
            let limit = if m.metallic() > 0.0 { 1.0 } else { 0.85 };
            assert!(m.albedo().iter().all(|&c| (0.0..=limit).contains(&c)), "{m:?}");
        }
    }

    #[test]
    fn reflection_factors_are_in_gltf_ranges_and_roughness_maps_share_a_textured_uv() {
        for m in Material::ALL {
            assert!([0.0, 1.0].contains(&m.metallic()), "{m:?}");
            assert!((0.0..=1.0).contains(&m.roughness()), "{m:?}");
            if let Some(map) = m.roughness_texture() {
                assert!(m.texture().is_some() && !map.is_base_colour(), "{m:?}");
            }
        }
    }

    #[test]
    fn all_lists_every_material_once_in_declaration_order() {
        for (i, m) in Material::ALL.iter().enumerate() {
            assert_eq!(*m as usize, i);
        }
        let mut names: Vec<&str> = Material::ALL.iter().map(|m| m.name()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), Material::ALL.len());
    }

    #[test]
    fn texture_repeats_are_powers_of_two() {
        for m in Material::ALL {
            if let Some((_, metres)) = m.texture() {
                assert!(metres > 0.0 && metres.log2().fract() == 0.0, "{m:?}: {metres}");
            }
        }
    }
}
