/// FiberOrientationMap: colour coding of direction and inclination (docs/pli-analysis.md §4) in the
/// HSV-black and RGB schemes of fastPLI, with the channel quantisation
/// q(x) = clamp(floor(255·x + 1e-6), 0, 255), plus a legend image in the same mapping.
/// Angles here are in degrees (they come straight from the VTK arrays, and H = 2·d mod 360 must
/// be exact for directions like 30°).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

/// ColorScheme (docs/api.md §1): HSV-black (default) or RGB.
enum class FomScheme
{
  HsvBlack = 0,
  Rgb = 1
};

/// "HSV-black" / "RGB" (docs/api.md §1 spelling) → scheme; false for any other text.
bool parseFomScheme(const std::string& name, FomScheme& scheme);
/// The spelling of a scheme (docs/api.md §1).
const char* fomSchemeName(FomScheme scheme);

struct Rgb8
{
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
};

/// docs/pli-analysis.md §4: colour of direction d and inclination i (degrees; the sign of i is
/// ignored, |i| > 90 is treated as 90). Any NaN input → black.
Rgb8 fomColor(double directionDeg, double inclinationDeg, FomScheme scheme);

/// FOM of n pixels: rgb receives 3·n bytes (r, g, b per pixel, the layout of a 3-component VTK
/// unsigned char array). OpenMP over pixels with `threads` (0 = all). Null pointers with n > 0 are
/// an error.
std::string fomMap(const double* directionDeg, const double* inclinationDeg, std::size_t n,
  FomScheme scheme, int threads, std::uint8_t* rgb);

/// Which pixels a FOM shows as background (black): none, those with retardation below a
/// threshold (no birefringent tissue), or those with transmittance above it (light passed
/// unhindered).
enum class FomMask
{
  None = 0,
  Retardation = 1,
  Transmittance = 2
};

/// Blackens the background pixels of an n-pixel FOM (rgb: 3·n bytes) and writes tissue[p] = 1 for
/// kept pixels, 0 for background (tissue may be null). `values` is the retardation or
/// transmittance image the mask is about (ignored for None); a NaN value is background. Error for
/// a null `values` with a mask or a non-finite threshold.
std::string fomApplyMask(const double* values, std::size_t n, FomMask mask, double threshold,
  std::uint8_t* rgb, std::uint8_t* tissue);

/// Largest finite value of values[0..n) (−∞ when there is none): what a mask threshold is a
/// fraction of (docs/pli-analysis.md §4).
double fomMaskReference(const double* values, std::size_t n);

/// The absolute threshold for fomApplyMask from `fraction` in [0, 1] of the image's largest value
/// `largest` (fomMaskReference, over all pieces of a split image): Retardation treats pixels below
/// fraction·largest as background, Transmittance those above (1 − fraction)·largest, i.e. within
/// `fraction` of the brightest (unattenuated) light. Without any finite value (largest −∞) the
/// threshold is 0: every pixel is NaN and so background anyway. Error for a fraction outside [0,
/// 1].
std::string fomMaskThreshold(FomMask mask, double fraction, double largest, double& threshold);

/// Legend (docs/pli-analysis.md §4): a size × size image (x fastest, row 0 at the bottom = y −1, as
/// vtkImageData) of the upper hemisphere seen from +z. Pixel centre (x, y) in [−1, 1]² inside the
/// unit disc gets d = atan2(y, x) folded into [0°, 180°) and i = asin(√(1 − x² − y²)); pixels
/// outside the disc get `background`. rgb is resized to 3·size². Error when size < 1 or size >
/// 16384.
std::string fomLegend(
  int size, FomScheme scheme, std::vector<std::uint8_t>& rgb, Rgb8 background = { 255, 255, 255 });

} // namespace fiberpli
