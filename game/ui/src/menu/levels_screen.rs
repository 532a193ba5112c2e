//! The level menu: every level the game found (shipped, the user's levels folder, `--levels-dir`),
//! each with its thumbnail, name, one-line description and where it lives. A level that fails
//! `headlamp check` is listed with its error and cannot be started.

use engine::egui::{self, Color32, RichText};

use super::widgets::{big_button, heading, panel};

/// What the level menu shows of one level; the game fills these in.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LevelCard {
    pub name: String,
    pub description: String,
    /// Where it is: "shipped", or the folder or archive.
    pub location: String,
    /// The first error `check` found: the level is listed but cannot be played.
    pub error: Option<String>,
}

/// The thumbnail's size in points (16:9).
pub const THUMBNAIL: egui::Vec2 = egui::vec2(160.0, 90.0);
const ERROR: Color32 = Color32::from_rgb(235, 110, 95);
const DIM: Color32 = Color32::from_gray(150);

#[derive(Default)]
pub(super) struct LevelsScreen {
    /// None while the game is still looking for levels.
    cards: Option<Vec<LevelCard>>,
    /// Per card, once rendered: the picture waiting to be uploaded, then its texture.
    thumbnails: Vec<Thumbnail>,
}

#[derive(Default)]
enum Thumbnail {
    #[default]
    None,
    Pending(egui::ColorImage),
    Shown(egui::TextureHandle),
}

impl LevelsScreen {
    pub fn set_cards(&mut self, cards: Vec<LevelCard>) {
        self.thumbnails = cards.iter().map(|_| Thumbnail::None).collect();
        self.cards = Some(cards);
    }

    pub fn cards(&self) -> Option<&[LevelCard]> {
        self.cards.as_deref()
    }

    /// The first playable card without a thumbnail: the one the game should render next.
    pub fn wants_thumbnail(&self) -> Option<usize> {
        let cards = self.cards.as_ref()?;
        (0..cards.len()).find(|&i| cards[i].error.is_none() && matches!(self.thumbnails[i], Thumbnail::None))
    }

    /// A card's picture (RGBA8, row-major), shown from the next frame on.
    pub fn set_thumbnail(&mut self, index: usize, width: usize, height: usize, rgba: &[u8]) {
        if let Some(slot) = self.thumbnails.get_mut(index) {
            *slot = Thumbnail::Pending(egui::ColorImage::from_rgba_unmultiplied([width, height], rgba));
        }
    }

    /// Draws the list; Some(index) when a level's Play was clicked, Some(None) on Back.
    pub fn show(&mut self, ctx: &egui::Context, esc: bool) -> Option<Option<usize>> {
        if esc {
            return Some(None);
        }
        let mut chosen = None;
        panel(ctx, "levels", |ui| {
            heading(ui, "Levels");
            match &self.cards {
                None => {
                    ui.label(RichText::new("Looking for levels…").color(DIM));
                }
                Some(cards) if cards.is_empty() => {
                    ui.label(RichText::new("No levels found").color(DIM));
                }
                Some(cards) => {
                    let height = (ctx.content_rect().height() * 0.65).max(200.0);
                    egui::ScrollArea::vertical().max_height(height).show(ui, |ui| {
                        for (i, card) in cards.iter().enumerate() {
                            if card_row(ui, card, &mut self.thumbnails[i], i) {
                                chosen = Some(Some(i));
                            }
                            ui.separator();
                        }
                    });
                }
            }
            ui.add_space(12.0);
            if big_button(ui, "Back") {
                chosen = Some(None);
            }
        });
        chosen
    }
}

/// One level: thumbnail, then name, description, location and error; true when Play is clicked.
fn card_row(ui: &mut egui::Ui, card: &LevelCard, thumbnail: &mut Thumbnail, index: usize) -> bool {
    if let Thumbnail::Pending(image) = thumbnail {
        let image = std::mem::take(image);
        *thumbnail =
            Thumbnail::Shown(ui.ctx().load_texture(format!("level thumbnail {index}"), image, Default::default()));
    }
    let mut play = false;
    ui.horizontal(|ui| {
        match thumbnail {
            Thumbnail::Shown(texture) => {
                ui.add(egui::Image::new(egui::load::SizedTexture::new(texture.id(), THUMBNAIL)));
            }
            _ => {
                let (rect, _) = ui.allocate_exact_size(THUMBNAIL, egui::Sense::hover());
                ui.painter().rect_filled(rect, 4.0, Color32::from_gray(35));
                let text = if card.error.is_some() { "—" } else { "…" };
                ui.painter().text(
                    rect.center(),
                    egui::Align2::CENTER_CENTER,
                    text,
                    egui::FontId::proportional(20.0),
                    DIM,
                );
            }
        }
        ui.vertical(|ui| {
            ui.set_max_width(420.0);
            ui.label(RichText::new(&card.name).size(20.0).strong().color(Color32::from_gray(235)));
            if !card.description.is_empty() {
                ui.label(RichText::new(&card.description).color(Color32::from_gray(200)));
            }
            ui.label(RichText::new(&card.location).small().color(DIM));
            match &card.error {
                Some(error) => {
                    ui.label(RichText::new(error).color(ERROR));
                }
                None => play = ui.button(RichText::new(format!("Play {}", card.name)).size(16.0)).clicked(),
            }
        });
    });
    play
}
