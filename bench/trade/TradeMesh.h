// vtkrtBenchTrade's meshes: the file read, the generated one, and the
// double-precision triangle copies the sections measure.
#ifndef vtkrtTradeMesh_h
#define vtkrtTradeMesh_h

#include "TradeCommon.h"

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <string>

namespace vtkrtTrade
{
/// Triangles only, points in double (so that translating by 1e8 loses
/// nothing in the data itself).
vtkSmartPointer<vtkPolyData> DoubleTriangles(vtkPolyData* input);

/// A sphere with bumps on every scale the decimation will remove.
vtkSmartPointer<vtkPolyData> BumpySphere(int res);

/// `mesh`'s triangles with every point moved by `offset`.
vtkSmartPointer<vtkPolyData> Translated(vtkPolyData* mesh, const Point& offset);

/// The triangles of a .ply, .obj, .stl or .vtp file in double; nullptr,
/// with a message on stderr, when the file cannot be read.
vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path);
}

#endif
