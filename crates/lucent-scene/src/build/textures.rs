//! From a texture description to the renderer's texture, reading image files once.

use super::Context;
use crate::desc::texture::{Encoding, ImageMapDesc, TextureDesc};
use crate::error::LoadError;
use lucent::Rgb;
use lucent::texture::{Channel, ImageMap, Texture, UvChecker, Wrap};
use std::ops::Range;

/// What a texture's values mean, which decides how an 8-bit image is decoded when its
/// `encoding` is not given.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    /// A colour: sRGB.
    Color,
    /// A number, a normal or a height: linear.
    Data,
}

impl Context<'_> {
    /// The texture of `d` for a parameter of kind `slot`; errors point at `span`.
    pub fn texture(
        &mut self,
        d: &TextureDesc,
        span: Range<usize>,
        slot: Slot,
    ) -> Result<Texture, LoadError> {
        Ok(match d {
            TextureDesc::Solid(c) => Texture::Solid(*c),
            TextureDesc::Checker(c) => Texture::Checker(*c),
            TextureDesc::Pattern(p) => Texture::Pattern(p.clone()),
            TextureDesc::Checkerboard {
                even,
                odd,
                placement,
            } => Texture::UvChecker(UvChecker {
                even: *even,
                odd: *odd,
                transform: placement.transform(),
            }),
            TextureDesc::Image(i) => Texture::Image(self.image_map(i, span, slot)?),
            TextureDesc::VertexColor => Texture::VertexColor,
            TextureDesc::Product(a, b) => Texture::Product(
                Box::new(self.texture(a, span.clone(), slot)?),
                Box::new(self.texture(b, span, slot)?),
            ),
            TextureDesc::Mix(a, b, t) => Texture::Mix {
                a: Box::new(self.texture(a, span.clone(), slot)?),
                b: Box::new(self.texture(b, span.clone(), slot)?),
                t: Box::new(self.texture(t, span, Slot::Data)?),
            },
            TextureDesc::Step(t, cutoff) => Texture::Step {
                value: Box::new(self.texture(t, span, slot)?),
                cutoff: *cutoff,
            },
        })
    }

    /// The lookup of an image description.
    fn image_map(
        &mut self,
        i: &ImageMapDesc,
        span: Range<usize>,
        slot: Slot,
    ) -> Result<ImageMap, LoadError> {
        let encoding = i.encoding.unwrap_or(match slot {
            Slot::Color => Encoding::Srgb,
            Slot::Data => Encoding::Linear,
        });
        let image = self.image_in(&i.file, i.gltf_image, span.clone(), Rgb::WHITE, encoding)?;
        let channel = i.channel.unwrap_or(Channel::Rgb);
        if channel == Channel::A
            && !self
                .builder
                .stored_image(image)
                .is_some_and(|img| img.has_alpha())
        {
            return Err(self
                .source
                .error(span, format!("`{}` has no alpha channel to read", i.file)));
        }
        Ok(ImageMap {
            image,
            transform: i.placement.transform(),
            wrap: i.wrap.unwrap_or([Wrap::Repeat; 2]),
            filter: i.filter.unwrap_or_default(),
            channel,
        })
    }
}
