/**
 * @class   vtkPLISimulation
 * @brief   3D-PLI simulation: the polarimeter's image stack of a tissue section voxelised from
 * fibers
 *
 * Input: fiber polydata (docs/data-contract.md §2: polylines with the point array `radius`,
 * optional cell array `bundle_id`). The fibers are voxelised into a section (layered capsules,
 * docs/pli-simulation.md §3), light is propagated through it with Müller matrices for every
 * polarizer angle and view (§4), then blurred, binned to camera pixels and given camera noise (§5).
 * All work is done by the Core (fiberpli::pli::runPLI).
 *
 * Output: vtkImageData with one slice (z extent 0..0), x and y in µm, spacing PixelSize. Point
 * arrays (double, one component per polarizer angle: RotationAngles, or k·180°/NumberOfRotations):
 * `intensity` (untilted view) and one `intensity_tilt_<v>` per tilted view (every tilt angle ×
 * every tilt azimuth, angle-major; by default the azimuths 0°, 90°, 180°, 270°). Field data:
 * `polarizer_angles` (deg), `tilt_angle` (deg, largest in-tissue θ_t = asin(sin θ / n), 0 =
 * untilted), `tilt_angles` and `tilt_directions` (deg, in-tissue θ_t and azimuth of every tilted
 * view), `section_thickness` (µm, n_z·VoxelSize), `wavelength` (nm),
 * `tilt_convention` (int, 0 = physical), `noise_gain`, `empty_section` (int), `voxel_size`,
 * `pixel_size` (µm), `light_intensity`.
 *
 * Output port 1 ("Tissue"), filled when ExportTissue is on: the voxelised tissue of TissueVolume as
 * vtkImageData on the voxel lattice (point = voxel centre, extent = global voxel indices), with
 * `label` and `optic_axis`, computed by the same Core column code as the rays read
 * (fiberpli::pli::exportTissue). A request on one port leaves the other port's data alone, so
 * looking at the tissue never re-runs the simulation.
 *
 * The image plane can be split (CAN_PRODUCE_SUB_EXTENT): any UPDATE_EXTENT gives exactly the crop
 * of the whole image, so MPI ranks compute their own pixels without communication; every rank asks
 * its input for piece 0 of 1 (all fibers). When VolumeOfInterest is the "input bounds" sentinel,
 * RequestInformation brings the input up to date (piece 0 of 1) to read its bounds, because the
 * image size depends on them.
 *
 * Bad input (missing `radius`, NaN, radius <= 0) and bad properties (VoxelSize <= 0, a
 * VolumeOfInterest with min > max on some axes only, sizes needing more than 16 GiB, bad Layers)
 * are errors naming the array, fiber or property; nothing is allocated and the output is empty. An
 * empty input gives an empty output. A section without fibers gives the background image and a
 * warning.
 */
#ifndef vtkPLISimulation_h
#define vtkPLISimulation_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkFiberSectionAlgorithm.h"

#include <memory> // for the plan
#include <string> // for TissueError
#include <vector> // for the angle lists

class vtkImageData;
namespace fiberpli
{
struct FiberModel;
namespace pli
{
struct PLIOptions;
struct PLIPlan;
}
}

class FIBERPLIFILTERS_EXPORT vtkPLISimulation : public vtkFiberSectionAlgorithm
{
public:
  static vtkPLISimulation* New();
  vtkTypeMacro(vtkPLISimulation, vtkFiberSectionAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Optic-axis interpolation along tilted rays (docs/pli-simulation.md §4.5).
  enum InterpolationType
  {
    NEAREST = 0,
    LINEAR = 1,
    SLERP = 2
  };

  // VolumeOfInterest, VoxelSize and PixelSize: the section (vtkFiberSectionAlgorithm).

  ///@{
  /**
   * Wavelength of the light, nm, > 0. Default is 525.
   */
  vtkSetMacro(Wavelength, double);
  vtkGetMacro(Wavelength, double);
  ///@}

  ///@{
  /**
   * Intensity I0 of the unpolarised light source, >= 0. Default is 26000.
   */
  vtkSetMacro(LightIntensity, double);
  vtkGetMacro(LightIntensity, double);
  ///@}

  ///@{
  /**
   * Number of polarizer angles N, 3 to 3600; angles k·180°/N. Used when RotationAngles is empty.
   * Default is 18.
   */
  vtkSetMacro(NumberOfRotations, int);
  vtkGetMacro(NumberOfRotations, int);
  ///@}

  ///@{
  /**
   * Polarizer angles, degrees, each in [0, 180), distinct, at least 3, in the order of the
   * components of the output arrays. Empty (the default) = NumberOfRotations equidistant angles.
   */
  void SetNumberOfRotationAngles(int n);
  void SetRotationAngle(int i, double degrees);
  int GetNumberOfRotationAngles() const { return static_cast<int>(this->RotationAngles.size()); }
  double GetRotationAngle(int i) const;
  ///@}

  ///@{
  /**
   * Tilt angle of the tilted views, degrees in [0, 45); 0 = no tilted views. Used when TiltAngles
   * is empty (the one-angle shorthand). Default is 0.
   */
  vtkSetMacro(TiltAngle, double);
  vtkGetMacro(TiltAngle, double);
  ///@}

  ///@{
  /**
   * Tilt angles of the specimen stage, degrees, each in (0, 45), distinct. Every tilt angle is
   * combined with every tilt azimuth: one tilted view per pair, angle-major. Empty (the default)
   * = TiltAngle alone.
   */
  void SetNumberOfTiltAngles(int n);
  void SetTiltAngleValue(int i, double degrees);
  int GetNumberOfTiltAngles() const { return static_cast<int>(this->TiltAngles.size()); }
  double GetTiltAngleValue(int i) const;
  ///@}

  ///@{
  /**
   * Tilt azimuths, degrees, each in [0, 360), distinct: the direction (counter-clockwise from +x
   * seen from +z) towards which the beam leans in the tissue. Empty (the default) = 0, 90, 180,
   * 270.
   */
  void SetNumberOfTiltAzimuths(int n);
  void SetTiltAzimuth(int i, double degrees);
  int GetNumberOfTiltAzimuths() const { return static_cast<int>(this->TiltAzimuths.size()); }
  double GetTiltAzimuth(int i) const;
  ///@}

  /// How the tilted beam sees the optic axis (docs/pli-simulation.md §4.3): 0 = physical (the beam
  /// frame of the tilted stage), 1 = fastPLI's (the transposed rotation, for comparisons).
  enum TiltConventionType
  {
    PHYSICAL = 0,
    FASTPLI = 1
  };

  ///@{
  /**
   * Tilt convention, PHYSICAL (default) or FASTPLI (other values are an error); written to the
   * field data tilt_convention, which PLIAnalysis follows.
   */
  vtkSetMacro(TiltConvention, int);
  vtkGetMacro(TiltConvention, int);
  ///@}

  ///@{
  /**
   * Fill output port 1 ("Tissue") with the voxelised tissue of TissueVolume: point arrays `label`
   * (int; 0 = embedding medium, 1 + b·L + l = layer l of the b-th bundle id in the field data
   * `label_bundle_ids`, L = `layers_per_bundle`) and `optic_axis` (3 floats, unit or 0 where there
   * is no axis), computed by the simulation's own voxeliser. Refused above the memory budget.
   * Default is 0 (port 1 empty).
   */
  vtkSetMacro(ExportTissue, int);
  vtkGetMacro(ExportTissue, int);
  vtkBooleanMacro(ExportTissue, int);
  ///@}

  ///@{
  /**
   * Sub-volume of the tissue port, µm: xmin xmax ymin ymax zmin zmax; the voxels whose centres lie
   * inside. min > max on every axis = the whole VolumeOfInterest. Default is (1, -1, 1, -1, 1, -1).
   */
  vtkSetVector6Macro(TissueVolume, double);
  vtkGetVector6Macro(TissueVolume, double);
  ///@}

  ///@{
  /**
   * Birefringence Δn of the fibers (one parallel layer) when Layers is empty. Fibers with the
   * point array inner_radius get the axon (no birefringence) inside it and the myelin sheath
   * (radial axis, Δn = -Birefringence) up to radius (docs/pli-simulation.md §3.2). Default is
   * -0.001.
   */
  vtkSetMacro(Birefringence, double);
  vtkGetMacro(Birefringence, double);
  ///@}

  ///@{
  /**
   * Absorption μ of the fibers when Layers is empty, 1/mm, >= 0. Default is 0.
   */
  vtkSetMacro(Absorption, double);
  vtkGetMacro(Absorption, double);
  ///@}

  ///@{
  /**
   * Seed of the camera noise, 0 to 2147483647 (negative is an error). Default is 0.
   */
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /**
   * Layered fiber model: groups separated by '|', optional "bundle_id:" prefix, ';'-separated
   * tuples "scale dn mu model" with model p (parallel), r (radial) or b (isotropic), e.g.
   * "0.666 0 5 b; 1 0.004 1 r". Overrides Birefringence and Absorption. Default is "" (none).
   */
  vtkSetStringMacro(Layers);
  vtkGetStringMacro(Layers);
  ///@}

  ///@{
  /**
   * Absorption of the embedding medium, 1/mm, >= 0. Default is 0.
   */
  vtkSetMacro(BackgroundAbsorption, double);
  vtkGetMacro(BackgroundAbsorption, double);
  ///@}

  ///@{
  /**
   * Ray step length, voxels, > 0. Default is 1.
   */
  vtkSetMacro(StepSize, double);
  vtkGetMacro(StepSize, double);
  ///@}

  ///@{
  /**
   * Optic-axis interpolation: 0 nearest, 1 linear, 2 spherical linear (Slerp); other values are
   * an error. Default is 2.
   */
  vtkSetMacro(Interpolation, int);
  vtkGetMacro(Interpolation, int);
  ///@}

  ///@{
  /**
   * Standard deviation of the Gaussian blur, output pixels, >= 0; 0 = no blur. Default is 0.71.
   */
  vtkSetMacro(OpticalSigma, double);
  vtkGetMacro(OpticalSigma, double);
  ///@}

  ///@{
  /**
   * Camera gain g (variance g·I): 0 = no noise, 1 = Poisson, > 1 = negative binomial. Default is 3.
   */
  vtkSetMacro(NoiseGain, double);
  vtkGetMacro(NoiseGain, double);
  ///@}

  ///@{
  /**
   * Refractive index of the tissue for the tilted beam, >= 1. Default is 1.
   */
  vtkSetMacro(RefractiveIndex, double);
  vtkGetMacro(RefractiveIndex, double);
  ///@}

  ///@{
  /**
   * Tilted views on the tilted sensor's grid (1) instead of registered onto the sample's pixel grid
   * (0, default): the camera looks at the tilted section along the tilted optical axis, so the
   * section appears foreshortened by cos(tilt) along the tilt azimuth about the image centre, same
   * PixelSize on the sensor (docs/pli-simulation.md §4.6). Written to the field data tilted_sensor;
   * PLIAnalysis refuses the tilt fit on such views.
   */
  vtkSetMacro(TiltedSensor, int);
  vtkGetMacro(TiltedSensor, int);
  vtkBooleanMacro(TiltedSensor, int);
  ///@}

  ///@{
  /**
   * Number of threads, 0 = all cores. Default is 0.
   */
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

protected:
  vtkPLISimulation();
  ~vtkPLISimulation() override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// This rank's part of RequestData (which makes its outcome collective under MPI).
  int ExecutePiece(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  vtkTypeBool ProcessRequest(
    vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkPLISimulation(const vtkPLISimulation&) = delete;
  void operator=(const vtkPLISimulation&) = delete;

  double Wavelength = 525.0;
  double LightIntensity = 26000.0;
  int NumberOfRotations = 18;
  std::vector<double> RotationAngles;
  double TiltAngle = 0.0;
  std::vector<double> TiltAngles;
  std::vector<double> TiltAzimuths;
  int TiltConvention = PHYSICAL;
  double Birefringence = -0.001;
  double Absorption = 0.0;
  int Seed = 0;
  char* Layers = nullptr;
  double BackgroundAbsorption = 0.0;
  double StepSize = 1.0;
  int Interpolation = SLERP;
  double OpticalSigma = 0.71;
  double NoiseGain = 3.0;
  double RefractiveIndex = 1.0;
  int TiltedSensor = 0;
  int NumberOfThreads = 0;

  int ExportTissue = 0;
  double TissueVolume[6] = { 1, -1, 1, -1, 1, -1 };

  /// The image part of the plan (options, section, views: planPLIImage), made by RequestInformation
  /// once per change of the properties or of the input's bounds (sentinel) and used by every
  /// RequestData (docs/pli-simulation.md §7.3).
  struct ImagePlan;
  std::unique_ptr<ImagePlan> Plan;
  void PlanImage(vtkInformationVector* inputVector);

  /// Port 0: the image stack of the update extent; port 1: the tissue of the update extent.
  /// claimsSolved: the input says it is collision-free, so overlapping tissue is worth a warning.
  int SimulateImage(const fiberpli::FiberModel& model, const fiberpli::pli::PLIOptions& options,
    const fiberpli::pli::PLIPlan& plan, const std::vector<std::string>& planWarnings,
    vtkInformation* outInfo, vtkImageData* output, bool claimsSolved);
  int VoxeliseTissue(const fiberpli::FiberModel& model, const fiberpli::pli::PLIOptions& options,
    const fiberpli::pli::PLIPlan& plan, vtkInformation* outInfo, vtkImageData* output);

  std::string TissueError; ///< bad or oversized TissueVolume found by RequestInformation, reported
                           ///< by RequestData
  /// Fibers this piece was computed from (periodic translates included) and fibers of the whole
  /// input: field data tile_fibers and model_fibers (docs/pli-simulation.md §6.3).
  double NumberOfTileFibers = 0.0;
  double NumberOfModelFibers = 0.0;
};

#endif
