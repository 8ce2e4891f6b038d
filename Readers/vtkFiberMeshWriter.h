/**
 * @class   vtkFiberMeshWriter
 * @brief   writes the fibers' surfaces as one ASCII PLY triangle mesh for diffusion simulators
 *
 * Input: fiber polydata (docs/data-contract.md §1). Output file: every fiber's outer surface (the
 * `radius` array) and, where the point array `inner_radius` exists and InnerSurfaces is on, the
 * axon surface inside it, as polygon tubes in one ASCII PLY whose vertex lines are `x y z` (µm) and
 * whose face lines are `3 i j k`, wound outward — what MC/DC reads (with `ply_scale 0.001`).
 * With a `periodic_cell` the tubes are cut at the cell faces and wrapped into the cell (closed
 * modulo the cell); otherwise they are capped (Core/Mesh/SubstrateMesher.h,
 * docs/diffusion-export.md §1). The mesh is counted first, then streamed to a temporary file that
 * replaces FileName when complete; the counts are reported. With WriteMCDCConfig an MC/DC
 * configuration snippet is written beside the mesh (`<name>.mcdc.conf`). With CylinderList the
 * fibers are also written as an MC/DC cylinder list (`<name>.cylinders.txt`,
 * Core/IO/McdcCylinders.h) when every fiber is straight within StraightnessTolerance; otherwise
 * nothing is written and the error names the fiber that deviates most.
 */
#ifndef vtkFiberMeshWriter_h
#define vtkFiberMeshWriter_h

#include "FiberPLIReadersModule.h" // for export macro
#include "vtkWriter.h"

#include <string> // for Fail

class FIBERPLIREADERS_EXPORT vtkFiberMeshWriter : public vtkWriter
{
public:
  static vtkFiberMeshWriter* New();
  vtkTypeMacro(vtkFiberMeshWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The .ply file to write. Default is none.
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Vertices per ring, 3 to 256. Default is 16 (the ring polygon then lies within 1.9 % of the
   * radius inside the circle and keeps 97.5 % of its area).
   */
  vtkSetMacro(NumberOfSides, int);
  vtkGetMacro(NumberOfSides, int);
  ///@}

  ///@{
  /**
   * Geometric tolerance in µm: when > 0 it replaces NumberOfSides by the fewest sides whose polygon
   * stays within the tolerance of the circle of the largest radius. Default is 0 (off).
   */
  vtkSetMacro(Tolerance, double);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * Largest distance between rings along a fiber in µm; 0 puts rings at the fiber's points only.
   * Default is 0.
   */
  vtkSetMacro(RingSpacing, double);
  vtkGetMacro(RingSpacing, double);
  ///@}

  ///@{
  /**
   * Also write the inner (axon) surface where the point array inner_radius exists. Default is on.
   */
  vtkSetMacro(InnerSurfaces, bool);
  vtkGetMacro(InnerSurfaces, bool);
  ///@}

  ///@{
  /**
   * Write an MC/DC configuration snippet (obstacle block with ply_scale 0.001 and the voxel in
   * mm) to `<name>.mcdc.conf` beside the mesh. Default is off.
   */
  vtkSetMacro(WriteMCDCConfig, bool);
  vtkGetMacro(WriteMCDCConfig, bool);
  ///@}

  /// What CylinderList writes beside the mesh.
  enum CylinderListKinds
  {
    CYLINDERS_NONE = 0,      ///< no list (the default)
    CYLINDERS_Z_ALIGNED = 1, ///< MC/DC cylinders_list: `x y z r`, axes parallel to z
    CYLINDERS_ORIENTED = 2   ///< MC/DC oriented_cylinders_list: `x y z ox oy oz r`
  };

  ///@{
  /**
   * Also write the fibers as an MC/DC cylinder list `<name>.cylinders.txt` beside the mesh (one
   * cylinder per fiber: its first point, or first and last point, and its largest radius; line 1
   * the scale 0.001 from µm to mm). Default is CYLINDERS_NONE.
   */
  vtkSetMacro(CylinderList, int);
  vtkGetMacro(CylinderList, int);
  ///@}

  ///@{
  /**
   * Largest distance in µm a fiber's points may have from its cylinder axis for CylinderList.
   * Default is 0.01.
   */
  vtkSetMacro(StraightnessTolerance, double);
  vtkGetMacro(StraightnessTolerance, double);
  ///@}

  ///@{
  /**
   * What the last Write() produced (counted before writing): vertices, triangles, bytes.
   */
  vtkGetMacro(VerticesWritten, double);
  vtkGetMacro(TrianglesWritten, double);
  vtkGetMacro(BytesWritten, double);
  ///@}

protected:
  vtkFiberMeshWriter() = default;
  ~vtkFiberMeshWriter() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

private:
  vtkFiberMeshWriter(const vtkFiberMeshWriter&) = delete;
  void operator=(const vtkFiberMeshWriter&) = delete;

  void WriteMesh(); // the work of WriteData, inside the exception guard
  void Fail(unsigned long code, const std::string& message);

  char* FileName = nullptr;
  int NumberOfSides = 16;
  double Tolerance = 0.0;
  double RingSpacing = 0.0;
  bool InnerSurfaces = true;
  bool WriteMCDCConfig = false;
  int CylinderList = CYLINDERS_NONE;
  double StraightnessTolerance = 0.01; // kMcdcDefaultStraightness
  double VerticesWritten = 0.0;
  double TrianglesWritten = 0.0;
  double BytesWritten = 0.0;
};

#endif
