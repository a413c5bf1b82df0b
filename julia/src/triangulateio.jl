# `TriangulateIO` (Triangulate.jl 3's public structure), its conversions to and from
# `CTriangulateIO`, and `triangulate`.

"""
    TriangulateIO

Triangle's `triangulateio` with Julia arrays, as in Triangulate.jl: arrays are column-major
with **one column per item** (a point, triangle, segment, ...), which is exactly Triangle's
memory layout, so input arrays are passed to the library without copying. All indices are
1-based (TriangleRS never passes Triangle's `z` switch); `-1` means "no neighbour" in
`neighborlist` and "infinite ray" in a Voronoi `edgelist`.

Fields (all optional on input except `pointlist`; empty arrays stand for "absent"):
- `pointlist::Matrix{Cdouble}`: 2×n point coordinates.
- `pointattributelist::Matrix{Cdouble}`: k×n point attributes.
- `pointmarkerlist::Vector{Cint}`: n point markers.
- `trianglelist::Matrix{Cint}`: 3×m (or 6×m with `o2`) corners, counterclockwise, then the
  mid-edge nodes (node 3+i lies on the edge opposite corner i). Input with `r`.
- `triangleattributelist::Matrix{Cdouble}`: k×m triangle attributes (regional with `A`).
- `trianglearealist::Vector{Cdouble}`: m area bounds, input only (`r` with `a` and no number).
- `neighborlist::Matrix{Cint}`: 3×m neighbours (`n`), neighbour i opposite corner i.
- `segmentlist::Matrix{Cint}`: 2×s segment endpoints (input with `p`).
- `segmentmarkerlist::Vector{Cint}`: s segment markers.
- `holelist::Matrix{Cdouble}`: 2×h hole points (input with `p`; the output shares this array).
- `regionlist::Matrix{Cdouble}`: 4×r regions: x, y, attribute, maximum area (shared likewise).
- `edgelist::Matrix{Cint}`: 2×e edges (`e`, or the Voronoi edges with `v`).
- `edgemarkerlist::Vector{Cint}`: e edge markers.
- `normlist::Matrix{Cdouble}`: 2×e ray directions of a Voronoi diagram ((0,0) for finite edges).
"""
mutable struct TriangulateIO
    pointlist::Matrix{Cdouble}
    pointattributelist::Matrix{Cdouble}
    pointmarkerlist::Vector{Cint}
    trianglelist::Matrix{Cint}
    triangleattributelist::Matrix{Cdouble}
    trianglearealist::Vector{Cdouble}
    neighborlist::Matrix{Cint}
    segmentlist::Matrix{Cint}
    segmentmarkerlist::Vector{Cint}
    holelist::Matrix{Cdouble}
    regionlist::Matrix{Cdouble}
    edgelist::Matrix{Cint}
    edgemarkerlist::Vector{Cint}
    normlist::Matrix{Cdouble}
end

"""
    TriangulateIO(; pointlist, pointattributelist, pointmarkerlist, trianglelist, ...)

A `TriangulateIO` with the given fields (any array convertible to the field's type, e.g.
`Float64[0 1 0; 0 0 1]` or `[1 2; 2 3]'`); the others are empty.
"""
function TriangulateIO(;
        pointlist = Matrix{Cdouble}(undef, 0, 0),
        pointattributelist = Matrix{Cdouble}(undef, 0, 0),
        pointmarkerlist = Vector{Cint}(undef, 0),
        trianglelist = Matrix{Cint}(undef, 0, 0),
        triangleattributelist = Matrix{Cdouble}(undef, 0, 0),
        trianglearealist = Vector{Cdouble}(undef, 0),
        neighborlist = Matrix{Cint}(undef, 0, 0),
        segmentlist = Matrix{Cint}(undef, 0, 0),
        segmentmarkerlist = Vector{Cint}(undef, 0),
        holelist = Matrix{Cdouble}(undef, 0, 0),
        regionlist = Matrix{Cdouble}(undef, 0, 0),
        edgelist = Matrix{Cint}(undef, 0, 0),
        edgemarkerlist = Vector{Cint}(undef, 0),
        normlist = Matrix{Cdouble}(undef, 0, 0),
    )
    # The default constructor converts each argument to its field's type.
    return TriangulateIO(
        pointlist, pointattributelist, pointmarkerlist,
        trianglelist, triangleattributelist, trianglearealist, neighborlist,
        segmentlist, segmentmarkerlist, holelist, regionlist,
        edgelist, edgemarkerlist, normlist,
    )
end

# A new `TriangulateIO` sharing `tio`'s arrays: a private view of the input that nobody can
# reassign while the library reads it.
shallow_copy(tio::TriangulateIO) =
    TriangulateIO((getfield(tio, name) for name in fieldnames(TriangulateIO))...)

function Base.show(io::IO, tio::TriangulateIO)
    println(io, "TriangulateIO(")
    for name in fieldnames(TriangulateIO)
        a = getfield(tio, name)
        if size(a, ndims(a)) > 0
            println(io, "    ", name, " = ", a, ",")
        end
    end
    print(io, ")")
end

"Number of points (columns of `pointlist`)."
numberofpoints(tio::TriangulateIO) = size(tio.pointlist, 2)

"Number of segments (columns of `segmentlist`)."
numberofsegments(tio::TriangulateIO) = size(tio.segmentlist, 2)

"Number of triangles (columns of `trianglelist`)."
numberoftriangles(tio::TriangulateIO) = size(tio.trianglelist, 2)

"Number of edges (columns of `edgelist`)."
numberofedges(tio::TriangulateIO) = size(tio.edgelist, 2)

"Number of regions (columns of `regionlist`)."
numberofregions(tio::TriangulateIO) = size(tio.regionlist, 2)

"Number of holes (columns of `holelist`)."
numberofholes(tio::TriangulateIO) = size(tio.holelist, 2)

"Number of attributes per triangle (rows of `triangleattributelist`)."
numberoftriangleattributes(tio::TriangulateIO) = size(tio.triangleattributelist, 1)

"""
    TriangulateError(msg)

Thrown by [`triangulate`](@ref) when the library reports an error (Triangle would have exited
the process); `msg` is the library's message, e.g. "Input must have at least three input
vertices.".
"""
struct TriangulateError <: Exception
    msg::String
end

TriangulateError() = TriangulateError("")

Base.showerror(io::IO, e::TriangulateError) =
    print(io, "TriangulateError: ", isempty(e.msg) ? "triangulation failed" : e.msg)

# The address of an input array, or NULL when it is empty.
array_pointer(a::Array{T}) where {T} = isempty(a) ? Ptr{T}(C_NULL) : pointer(a)

function check_items(what::String, a::AbstractArray, width::Int)
    if size(a, 2) > 0 && size(a, 1) != width
        throw(ArgumentError("$what must have $width rows (one column per item), has size $(size(a))"))
    end
    return size(a, 2)
end

function check_count(what::String, a::AbstractArray, items::Int, of::String)
    if size(a, ndims(a)) != items
        throw(ArgumentError("$what has $(size(a, ndims(a))) items but there are $items $of"))
    end
    return nothing
end

# The C view of `tio`'s arrays (no copies). The caller keeps `tio`'s arrays alive while the
# result is in use (`GC.@preserve`).
function CTriangulateIO(tio::TriangulateIO)
    ctio = CTriangulateIO()

    npoints = check_items("pointlist", tio.pointlist, 2)
    ctio.numberofpoints = npoints
    ctio.pointlist = array_pointer(tio.pointlist)
    nattributes = size(tio.pointattributelist, 1)
    if nattributes > 0
        check_count("pointattributelist", tio.pointattributelist, npoints, "points")
        ctio.numberofpointattributes = nattributes
        ctio.pointattributelist = array_pointer(tio.pointattributelist)
    end
    if !isempty(tio.pointmarkerlist)
        check_count("pointmarkerlist", tio.pointmarkerlist, npoints, "points")
        ctio.pointmarkerlist = array_pointer(tio.pointmarkerlist)
    end

    ntriangles = size(tio.trianglelist, 2)
    if ntriangles > 0
        ctio.numberoftriangles = ntriangles
        ctio.numberofcorners = size(tio.trianglelist, 1)
        ctio.trianglelist = array_pointer(tio.trianglelist)
        ntriangleattributes = size(tio.triangleattributelist, 1)
        if ntriangleattributes > 0
            check_count("triangleattributelist", tio.triangleattributelist, ntriangles, "triangles")
            ctio.numberoftriangleattributes = ntriangleattributes
            ctio.triangleattributelist = array_pointer(tio.triangleattributelist)
        end
        if !isempty(tio.trianglearealist)
            check_count("trianglearealist", tio.trianglearealist, ntriangles, "triangles")
            ctio.trianglearealist = array_pointer(tio.trianglearealist)
        end
    end

    nsegments = check_items("segmentlist", tio.segmentlist, 2)
    ctio.numberofsegments = nsegments
    ctio.segmentlist = array_pointer(tio.segmentlist)
    if nsegments > 0 && !isempty(tio.segmentmarkerlist)
        check_count("segmentmarkerlist", tio.segmentmarkerlist, nsegments, "segments")
        ctio.segmentmarkerlist = array_pointer(tio.segmentmarkerlist)
    end

    ctio.numberofholes = check_items("holelist", tio.holelist, 2)
    ctio.holelist = array_pointer(tio.holelist)
    ctio.numberofregions = check_items("regionlist", tio.regionlist, 4)
    ctio.regionlist = array_pointer(tio.regionlist)
    return ctio
end

# Takes ownership of an array the library allocated: Julia's GC frees it with libc `free`.
# An empty one is freed now (wrapping zero elements does not reliably own the buffer).
function take_array(p::Ptr{T}, dims::NTuple{N,Int}) where {T,N}
    if p == C_NULL
        return Array{T,N}(undef, ntuple(_ -> 0, N))
    elseif any(iszero, dims)
        trifree(p)
        return Array{T,N}(undef, ntuple(_ -> 0, N))
    end
    return unsafe_wrap(Array, p, dims; own = true)
end

# `holelist`/`regionlist` of the output: the library copied the input's pointer. Share the
# input's Julia array when it is that one (no copy, and it stays alive as long as either
# structure); otherwise (a raw `CTriangulateIO` from elsewhere) wrap it without owning it.
function aliased_array(p::Ptr{Cdouble}, rows::Int, items::Int, input::Union{Matrix{Cdouble},Nothing})
    if p == C_NULL || items == 0
        return Matrix{Cdouble}(undef, 0, 0)
    elseif input !== nothing && !isempty(input) && p == pointer(input)
        return input
    end
    return unsafe_wrap(Array, p, (rows, items); own = false)
end

"""
    TriangulateIO(ctio::CTriangulateIO; input = nothing)

Takes ownership of the arrays the library allocated in `ctio` (each is freed by Julia's GC)
and clears them from `ctio`. `holelist` and `regionlist` are not owned: they alias the input
(`input`, the `TriangulateIO` that was triangulated, whose arrays are then shared).
"""
function TriangulateIO(ctio::CTriangulateIO; input::Union{TriangulateIO,Nothing} = nothing)
    npoints = Int(ctio.numberofpoints)
    ntriangles = Int(ctio.numberoftriangles)
    nsegments = Int(ctio.numberofsegments)
    nedges = Int(ctio.numberofedges)
    tio = TriangulateIO(;
        pointlist = take_array(ctio.pointlist, (2, npoints)),
        pointattributelist = take_array(ctio.pointattributelist, (Int(ctio.numberofpointattributes), npoints)),
        pointmarkerlist = take_array(ctio.pointmarkerlist, (npoints,)),
        trianglelist = take_array(ctio.trianglelist, (Int(ctio.numberofcorners), ntriangles)),
        triangleattributelist = take_array(ctio.triangleattributelist, (Int(ctio.numberoftriangleattributes), ntriangles)),
        trianglearealist = take_array(ctio.trianglearealist, (ntriangles,)),
        neighborlist = take_array(ctio.neighborlist, (3, ntriangles)),
        segmentlist = take_array(ctio.segmentlist, (2, nsegments)),
        segmentmarkerlist = take_array(ctio.segmentmarkerlist, (nsegments,)),
        holelist = aliased_array(ctio.holelist, 2, Int(ctio.numberofholes), input === nothing ? nothing : input.holelist),
        regionlist = aliased_array(ctio.regionlist, 4, Int(ctio.numberofregions), input === nothing ? nothing : input.regionlist),
        edgelist = take_array(ctio.edgelist, (2, nedges)),
        edgemarkerlist = take_array(ctio.edgemarkerlist, (nedges,)),
        normlist = take_array(ctio.normlist, (2, nedges)),
    )
    # Everything allocated now belongs to `tio`: clear the pointers so nothing frees twice.
    for name in ALLOCATED_FIELDS
        setproperty!(ctio, name, C_NULL)
    end
    return tio
end

"""
    triangulate(switches, triin::TriangulateIO; unsuitable) -> (triout, vorout)

Triangulates, meshes or refines `triin` as Triangle 1.6 does with the command-line
`switches` (without the dash; see `triangle -h`), e.g. `"pq30a0.01Q"`. Returns the mesh and
the Voronoi diagram (filled only with `v`). Output arrays are owned by Julia; `holelist` and
`regionlist` of `triout` are `triin`'s arrays (Triangle copies their pointers).

Throws [`TriangulateError`](@ref) with the library's message on an error (the process never
exits). Differences from Triangulate.jl: the `z` switch is accepted and has no effect, since
indices are always 1-based here (Triangulate.jl hands it to Triangle, and its output is then
numbered from 0); the order of output triangles, edges and new points differs from Triangle's;
the `u` test is `unsuitable` if given, else the current task's (see [`triunsuitable!`](@ref)).

Numbers after switches may use exponent notation (`"a1e-5"` is the area bound 1e-5; Triangle
reads it as `a1` followed by the switch `e`), and are read independently of the C locale.
Fixed notation (`@sprintf("a%.15f", area)`) means the same to both libraries.
"""
function triangulate(switches::AbstractString, triin::TriangulateIO; unsuitable = current_unsuitable())
    # `z` (number from 0) would make the library read and write 0-based indices; Julia's are
    # 1-based, so it is dropped. No number after a switch contains a `z`.
    switch_string = replace(String(switches), "z" => "")
    input = shallow_copy(triin)
    ctio_out = CTriangulateIO()
    vor_out = CTriangulateIO()
    call = UnsuitableCall(unsuitable)
    rc, message = GC.@preserve input begin
        ctio_in = CTriangulateIO(input)
        triangulate_reentrant!(switch_string, ctio_in, ctio_out, vor_out, call)
    end
    if rc != 0
        # The library frees its partial results on error; free whatever it may have left.
        free_allocated!(ctio_out)
        free_allocated!(vor_out)
        call.failure === nothing || throw(call.failure)
        throw(TriangulateError(message))
    end
    triout = TriangulateIO(ctio_out; input = input)
    vorout = TriangulateIO(vor_out; input = input)
    call.failure === nothing || throw(call.failure)
    return triout, vorout
end
