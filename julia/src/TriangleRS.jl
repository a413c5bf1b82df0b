"""
    TriangleRS

Two-dimensional Delaunay triangulation and quality meshing with the API of Triangulate.jl 3,
computed by triangle-rs (a Rust reimplementation of Jonathan Shewchuk's Triangle 1.6 behind
Triangle's C ABI).

```julia
using TriangleRS
triin = TriangulateIO(; pointlist = Cdouble[0 1 1 0; 0 0 1 1])
triout, vorout = triangulate("Q", triin)
```

Differences from Triangulate.jl: errors never exit the process and carry Triangle's message
(`TriangulateError(msg)`); the `u` test is passed to the library per call, so
[`triunsuitable!`](@ref) is safe across tasks and threads; the element order of the output
differs from Triangle's (the mesh is the same up to order where it is unique).
"""
module TriangleRS

using Libdl: Libdl
using Preferences: @load_preference, @set_preferences!, @delete_preferences!

include("library.jl")
include("unsuitable.jl")
include("ctriangulateio.jl")
include("triangulateio.jl")

export triangulate
export triunsuitable!
export TriangulateIO
export numberofpoints
export numberofsegments
export numberoftriangles
export TriangulateError

# Triangulate.jl's unexported helpers, and this package's library selection, as public names.
@static if VERSION >= v"1.11.0-DEV.469"
    eval(Meta.parse("""
        public CTriangulateIO, numberofedges, numberofregions, numberofholes,
               numberoftriangleattributes, library_path, set_library_path!
        """))
end

end # module TriangleRS
