//! The shipped levels' materials: a diffuse albedo each (the glTF base colour factor), and for
//! the textured ones a procedural base colour texture that multiplies it.

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
}

impl Material {
    pub const ALL: [Material; 17] = [
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
        }
    }

    /// Linear diffuse albedo (the base colour factor). Kept at or below 0.85 so multi-bounce GI
    /// stays well behaved; a texture (values at most 1) only darkens it.
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
            Material::Stone => Some((TextureKind::Stone, 2.0)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn albedos_are_matte_and_below_085() {
        for m in Material::ALL {
            assert!(m.albedo().iter().all(|&c| (0.0..=0.85).contains(&c)), "{m:?}");
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
