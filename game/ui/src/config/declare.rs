//! The macro that turns the one list of config keys (in `config.rs`) into the
//! [`Config`](super::Config) struct and what the file needs of it, so that a key's name, type,
//! default, range and comment are written once.
//!
//! It names nothing of `config.rs` (which invokes it): its expansion names only the generic
//! machinery of [`super::format`] and [`super::sections`] and what the invoker passes in, so
//! that no two of the config, its macro, the format and the sections import each other.

/// Declares [`Config`](super::Config) from one list in two parts. `keys`: the plain sections, in
/// the file's order, each a `[section]` line and then one entry a key:
///
/// ```text
/// /// Documentation of the field (optional).
/// field as key: f32 = default, in RANGE_NAME = min..=max, "comment above the key ({range})";
/// ```
///
/// `as key` names the key when it is not the field's name; `in RANGE_NAME` gives the range of a
/// number (`= min..=max` declares the constant `Config::RANGE_NAME`, without it the entry shares
/// one declared before); the comment is optional. The types are `f32` and `bool`
/// ([`super::format::KeyValue`]). `sections`: `field: Type = default;` for values that fill
/// sections of their own, written after the plain ones in the list's order.
///
/// It gives the struct, its `Default`, the range constants, and the tables the file's writer
/// and parser work from: `PLAIN_SECTIONS`, `KEYS` and `OWNERS`.
macro_rules! config_file {
    (@key_name $field:ident) => { stringify!($field) };
    (@key_name $field:ident $key:ident) => { stringify!($key) };
    (@some) => { None };
    (@some $($value:tt)+) => { Some($($value)+) };
    (
        $(#[$struct_attr:meta])*
        pub struct $name:ident {
            keys {
                $(
                    [$section:ident]
                    $(
                        $(#[$attr:meta])*
                        $field:ident $(as $key:ident)?: $ty:ty = $default:expr
                            $(, in $range:ident $(= $min:literal..=$max:literal)?)?
                            $(, $comment:literal)?;
                    )*
                )*
            }
            sections {
                $(
                    $(#[$own_attr:meta])*
                    $own:ident: $own_ty:ty = $own_default:expr;
                )*
            }
        }
    ) => {
        $(#[$struct_attr])*
        pub struct $name {
            $($(
                $(#[$attr])*
                pub $field: $ty,
            )*)*
            $(
                $(#[$own_attr])*
                pub $own: $own_ty,
            )*
        }

        impl Default for $name {
            fn default() -> Self {
                Self { $($($field: $default,)*)* $($own: $own_default,)* }
            }
        }

        impl $name {
            $($($($(
                pub const $range: std::ops::RangeInclusive<f32> = $min..=$max;
            )?)?)*)*
        }

        /// The plain sections, in the file's order.
        const PLAIN_SECTIONS: &[&str] = &[$(stringify!($section)),*];

        /// Every key of the plain sections, in the file's order.
        const KEYS: &[$crate::config::format::Key<$name>] = &[$($(
            $crate::config::format::Key {
                section: stringify!($section),
                name: $crate::config::declare::config_file!(@key_name $field $($key)?),
                comment: $crate::config::declare::config_file!(@some $($comment)?),
                range: $crate::config::declare::config_file!(@some $($name::$range)?),
                write: |c| $crate::config::format::KeyValue::write(&c.$field),
                read: |c, value, key| {
                    c.$field = $crate::config::format::KeyValue::read(value, key)?;
                    Ok(())
                },
            },
        )*)*];

        /// The fields that fill sections of their own, in the file's order.
        const OWNERS: &[$crate::config::format::Owner<$name>] = &[$(
            $crate::config::format::Owner {
                sections: <$own_ty as $crate::config::sections::OwnSections>::SECTIONS,
                write: |c, out| $crate::config::sections::OwnSections::write(&c.$own, out),
                read: |c, file| $crate::config::sections::OwnSections::read(&mut c.$own, file),
            },
        )*];
    };
}

pub(super) use config_file;
