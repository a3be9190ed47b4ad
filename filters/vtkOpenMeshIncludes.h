// Brackets for #include lines of OpenMesh headers, shared by the filters and
// their tests. OpenMesh's headers are not warning-clean under -Wall -Wextra:
// this keeps their noise out of our build log without silencing our own code.
//
//   VTKRT_OPENMESH_INCLUDES_BEGIN
//   #include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
//   VTKRT_OPENMESH_INCLUDES_END
#ifndef vtkOpenMeshIncludes_h
#define vtkOpenMeshIncludes_h

#if defined(__GNUC__)
#define VTKRT_OPENMESH_INCLUDES_BEGIN                                                              \
  _Pragma("GCC diagnostic push") _Pragma("GCC diagnostic ignored \"-Wall\"")                      \
    _Pragma("GCC diagnostic ignored \"-Wextra\"") _Pragma("GCC diagnostic ignored \"-Wshadow\"")  \
      _Pragma("GCC diagnostic ignored \"-Wunused-parameter\"")                                    \
        _Pragma("GCC diagnostic ignored \"-Wdeprecated-copy\"")                                   \
          _Pragma("GCC diagnostic ignored \"-Wsign-compare\"")
#define VTKRT_OPENMESH_INCLUDES_END _Pragma("GCC diagnostic pop")
#else
#define VTKRT_OPENMESH_INCLUDES_BEGIN
#define VTKRT_OPENMESH_INCLUDES_END
#endif

#endif
// VTK-HeaderTest-Exclude: vtkOpenMeshIncludes.h
