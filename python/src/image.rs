//! Films and numpy arrays: a render's film handed to numpy, and arrays made films again to be
//! written as `lucent render` writes its images.

use lucent::Rgb;
use lucent::film::Film;
use lucent_cli::output::ImageFormat;
use numpy::ndarray::Array3;
use numpy::{PyArray3, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The film's linear radiance as an H×W×3 array, rows from the top: the film's one linear copy
/// (as `lucent render` makes for a PFM), handed to numpy without another.
pub fn to_array<'py>(py: Python<'py>, film: &Film) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let (w, h) = (film.width() as usize, film.height() as usize);
    let pixels = py.detach(|| film.to_linear_rgb().into_flattened());
    let array = Array3::from_shape_vec((h, w, 3), pixels)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(PyArray3::from_owned_array(py, array))
}

/// A film whose pixels are the array's values (one sample of weight 1 each: the film gives
/// finite values back exactly; NaN and infinite ones are left out, as a render's are).
pub fn to_film(pixels: &PyReadonlyArray3<'_, f32>) -> PyResult<Film> {
    let shape = pixels.shape();
    if shape[2] != 3 {
        return Err(PyValueError::new_err(format!(
            "an image is an H×W×3 array, not {}×{}×{}",
            shape[0], shape[1], shape[2]
        )));
    }
    let too_big = |n: usize| n == 0 || n > 65536;
    if too_big(shape[0]) || too_big(shape[1]) {
        return Err(PyValueError::new_err(format!(
            "an image is 1 to 65536 pixels wide and high, not {}×{}",
            shape[1], shape[0]
        )));
    }
    let (h, w) = (shape[0] as u32, shape[1] as u32);
    let a = pixels.as_array();
    let mut film = Film::new(w, h);
    for y in 0..h {
        for x in 0..w {
            let (r, g, b) = (
                a[[y as usize, x as usize, 0]],
                a[[y as usize, x as usize, 1]],
                a[[y as usize, x as usize, 2]],
            );
            film.add_sample(x, y, Some(Rgb::new(r, g, b)), 1.0);
        }
    }
    Ok(film)
}

/// The film as the PNG file `lucent render` writes (sRGB, 8 bits), in memory.
pub fn png(film: &Film) -> anyhow::Result<Vec<u8>> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    lucent_cli::output::encode_image(film, ImageFormat::Png, &mut bytes)?;
    Ok(bytes.into_inner())
}
