//! Mitsuba 3 XML (placeholder until the importer lands).

use crate::error::LoadError;
use crate::hash::Fingerprint;
use crate::import::Imported;
use crate::paths::LoadOptions;
use std::path::Path;

/// The scene of a Mitsuba 3 XML file.
pub fn import_mitsuba(
    path: &Path,
    _options: &LoadOptions,
    _inputs: &mut Fingerprint,
) -> Result<Imported, LoadError> {
    Err(LoadError::file(path, "Mitsuba XML files are not read yet"))
}
