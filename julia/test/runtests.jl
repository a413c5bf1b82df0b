# The cases of Triangulate.jl's test suite (test/test_*.jl), asserted as facts about the mesh
# rather than Triangle's element order, which triangle-rs does not reproduce.
#
# Run from the repository root after `cargo build --release --lib`:
#     julia --project=julia -e 'using Pkg; Pkg.test()'
# (or set TRIANGLE_RS_LIBRARY to another build). ctests/julia_calls.c makes the same library
# calls from C and runs in `cargo test`, on machines without Julia.

using Test
using TriangleRS
using TriangleRS: CTriangulateIO, numberofedges

# Thrown by an unsuitable test to check that exceptions cross the library cleanly.
struct StopMeshing <: Exception end

# The counts of the diamond meshed with paAqQ. Triangle 1.6 gives 177 points, 319 triangles and
# 33 segments; a quality mesh is not unique, so triangle-rs must land in a band around those.
# The diamond is a disc whose boundary edges are the segments: Euler's formula ties the counts.
function check_refined_diamond_counts(points, triangles, segments)
    @test 106 <= points <= 266
    @test 191 <= triangles <= 479
    @test 20 <= segments <= 50
    @test iseven(3 * triangles + segments) && points - (3 * triangles + segments) ÷ 2 + triangles == 1
end

# Twice the signed area of the triangle (a, b, c) of `points` (positive if counterclockwise).
function twice_area(points, a, b, c)
    return (points[1, b] - points[1, a]) * (points[2, c] - points[2, a]) -
           (points[2, b] - points[2, a]) * (points[1, c] - points[1, a])
end

# The exact orientation of (a, b, c), +1 counterclockwise: rounded arithmetic is not enough, as
# the ten attribute points hold a triangle whose doubled area is 2^-53.
function exact_orientation(points, a, b, c)
    x(i) = Rational{BigInt}(points[1, i])
    y(i) = Rational{BigInt}(points[2, i])
    return sign((x(b) - x(a)) * (y(c) - y(a)) - (y(b) - y(a)) * (x(c) - x(a)))
end

triangle_areas(tio) =
    [twice_area(tio.pointlist, tio.trianglelist[1, t], tio.trianglelist[2, t], tio.trianglelist[3, t]) / 2
     for t in 1:numberoftriangles(tio)]

# A triangle as its corners rotated to start at the smallest index (orientation kept).
function canonical(a, b, c)
    m = min(a, b, c)
    return m == a ? (a, b, c) : m == b ? (b, c, a) : (c, a, b)
end

triangle_set(tio) =
    Set(canonical(tio.trianglelist[1, t], tio.trianglelist[2, t], tio.trianglelist[3, t])
        for t in 1:numberoftriangles(tio))

segment_set(tio) =
    Set(minmax(tio.segmentlist[1, s], tio.segmentlist[2, s]) for s in 1:numberofsegments(tio))

function angle_at(points, a, b, c)  # the angle at corner a, in degrees
    u = points[:, b] - points[:, a]
    v = points[:, c] - points[:, a]
    return atand(abs(u[1] * v[2] - u[2] * v[1]), u[1] * v[1] + u[2] * v[2])
end

function minimum_angle(tio)
    p, t = tio.pointlist, tio.trianglelist
    return minimum(min(angle_at(p, t[1, k], t[2, k], t[3, k]), angle_at(p, t[2, k], t[3, k], t[1, k]),
                       angle_at(p, t[3, k], t[1, k], t[2, k])) for k in 1:numberoftriangles(tio))
end

# Checks that `tio` is a valid mesh: 1-based corner indices in range, counterclockwise
# triangles (or flat ones, if allowed), no two triangles over one another (each directed edge
# used once), the given total area, every segment an edge of the mesh, neighbours consistent.
# Returns the directed edges.
function check_mesh(tio; area = nothing, allow_flat = false)
    points, triangles = tio.pointlist, tio.trianglelist
    npoints, ntriangles = numberofpoints(tio), numberoftriangles(tio)
    @test size(points, 1) == 2
    @test ntriangles > 0
    @test size(triangles, 1) in (3, 6)
    @test all(i -> 1 <= i <= npoints, triangles)
    lowest = allow_flat ? 0 : 1
    @test all(t -> exact_orientation(points, triangles[1, t], triangles[2, t], triangles[3, t]) >= lowest, 1:ntriangles)
    directed = Dict{Tuple{Cint,Cint},Int}()
    edges_used_twice = 0
    for t in 1:ntriangles, (i, j) in ((1, 2), (2, 3), (3, 1))
        edge = (triangles[i, t], triangles[j, t])
        edges_used_twice += haskey(directed, edge)
        directed[edge] = t
    end
    @test edges_used_twice == 0
    area === nothing || @test isapprox(sum(triangle_areas(tio)), area; rtol = 1e-12)
    @test all(s -> haskey(directed, (tio.segmentlist[1, s], tio.segmentlist[2, s])) ||
                   haskey(directed, (tio.segmentlist[2, s], tio.segmentlist[1, s])), 1:numberofsegments(tio))
    if !isempty(tio.neighborlist)
        @test size(tio.neighborlist) == (3, ntriangles)
        consistent = true
        for t in 1:ntriangles, corner in 1:3
            # Neighbour `corner` is across the edge opposite that corner.
            a, b = triangles[mod1(corner + 1, 3), t], triangles[mod1(corner + 2, 3), t]
            expected = get(directed, (b, a), -1)
            consistent &= tio.neighborlist[corner, t] == expected
        end
        @test consistent
    end
    return directed
end

@testset "TriangleRS" begin
    @testset "library" begin
        @test isfile(TriangleRS.library_path())
    end

    @testset "diamond with a region, paAqQ (test_triangulate)" begin
        triin = TriangulateIO()
        triin.pointlist = Matrix{Float64}([1.0 0.0; 0.0 1.0; -1.0 0.0; 0.0 -1.0]')
        triin.segmentlist = Matrix{Int32}([1 2; 2 3; 3 4; 4 1]')
        triin.segmentmarkerlist = Vector{Int32}([1, 2, 3, 4])
        triin.regionlist = Matrix{Float64}([0.5 0.5 1 0.01;]')
        let
            triout, vorout = triangulate("paAqQ", triin)
            check_mesh(triout; area = 2.0)
            check_refined_diamond_counts(numberofpoints(triout), numberoftriangles(triout), numberofsegments(triout))
            @test length(triout.segmentmarkerlist) == numberofsegments(triout)
            @test triout.pointlist[:, 1:4] == triin.pointlist
            @test maximum(triangle_areas(triout)) <= 0.01 * (1 + 1e-12)
            @test minimum_angle(triout) >= 20 - 1e-9
            @test size(triout.triangleattributelist) == (1, numberoftriangles(triout))
            @test all(==(1.0), triout.triangleattributelist)
            @test all(in(1:4), triout.segmentmarkerlist)
            @test triout.regionlist === triin.regionlist  # shared, not copied or owned
            @test isempty(vorout.pointlist)
        end
    end

    @testset "raw CTriangulateIO, paAqQ (test_ctriangulate)" begin
        nodes = Matrix{Cdouble}([1.0 0.0; 0.0 1.0; -1.0 0.0; 0.0 -1.0]')
        faces = Matrix{Cint}([1 2; 2 3; 3 4; 4 1]')
        faceregions = Matrix{Cint}([1 2 3 4]')
        regionpoints = Matrix{Cdouble}([0.5 0.5 1 0.01;]')
        triin, triout, vorout = CTriangulateIO(), CTriangulateIO(), CTriangulateIO()
        rc, message = GC.@preserve nodes faces faceregions regionpoints begin
            triin.numberofpoints = size(nodes, 2)
            triin.pointlist = pointer(nodes)
            triin.numberofsegments = size(faces, 2)
            triin.segmentlist = pointer(faces)
            triin.segmentmarkerlist = pointer(faceregions)
            triin.numberofregions = size(regionpoints, 2)
            triin.regionlist = pointer(regionpoints)
            code = TriangleRS.triangulate("paAqQ", triin, triout, vorout)
            code, TriangleRS.last_error_message(TriangleRS.library())
        end
        @test rc == 0 && message == ""
        check_refined_diamond_counts(triout.numberofpoints, triout.numberoftriangles, triout.numberofsegments)
        @test triout.regionlist == pointer(regionpoints)
        @test triout.holelist == C_NULL
        # Taking ownership frees the library's arrays with Julia's GC (not the alias).
        owned = TriangulateIO(triout)
        @test numberoftriangles(owned) == triout.numberoftriangles
        @test triout.pointlist == C_NULL
        check_mesh(owned; area = 2.0)
        TriangleRS.free_allocated!(triout)
        TriangleRS.free_allocated!(vorout)
    end

    @testset "T-shaped PSLG without segment markers, pcDQ (test_triangulate2)" begin
        triin = TriangulateIO(; pointlist = Float64[0.0 1.0 2.0 1.0; 0.0 0.0 0.0 1.0],
                                segmentlist = Int32[1 2 2; 2 3 4])
        let
            triout, _ = triangulate("pcDQ", triin)
            check_mesh(triout; area = 1.0)
            @test numberofpoints(triout) == 4
            @test numberoftriangles(triout) == 2
            @test numberofsegments(triout) == 5
            @test triangle_set(triout) == Set([(1, 2, 4), (2, 3, 4)])
            @test segment_set(triout) == Set([(1, 2), (2, 3), (2, 4), (3, 4), (1, 4)])
        end
    end

    @testset "two points are an error (test_triangulate_catch_exit)" begin
        triin = TriangulateIO(; pointlist = [1.0 0.0; 0.0 1.0])
        @test_throws TriangulateError triangulate("Q", triin)
        err = try
            triangulate("Q", triin)
        catch e
            e
        end
        @test err isa TriangulateError
        @test typeof(err) == TriangulateError           # Triangulate.jl's own test checks this
        @test occursin("at least three", err.msg)
        @test occursin("TriangulateError", sprint(showerror, err))
    end

    @testset "two points, raw call returns 1 (test_ctriangulate_catch_exit)" begin
        nodes = Matrix{Cdouble}([1.0 0.0; 0.0 1.0;])
        triin, triout, vorout = CTriangulateIO(), CTriangulateIO(), CTriangulateIO()
        rc = GC.@preserve nodes begin
            triin.numberofpoints = Cint(size(nodes, 2))
            triin.pointlist = pointer(nodes)
            TriangleRS.triangulate("", triin, triout, vorout)
        end
        @test rc == 1
        @test triout.pointlist == C_NULL && triout.trianglelist == C_NULL
    end

    square = Cdouble[0.0 0.0; 1.0 0.0; 1.0 1.0; 0.0 1.0]'
    square_segments = Cint[1 2; 2 3; 3 4; 4 1]'

    @testset "unit square neighbours, pqQn (test_neighbors)" begin
        triin = TriangulateIO(; pointlist = square, segmentlist = square_segments,
                                segmentmarkerlist = Cint[1, 2, 3, 4])
        let
            triout, _ = triangulate("pqQn", triin)
            check_mesh(triout; area = 1.0)   # also checks neighborlist against the triangles
            @test triout.pointlist == square
            @test numberoftriangles(triout) == 2
            @test size(triout.neighborlist) == (3, 2)
            @test count(==(-1), triout.neighborlist) == 4
            markers = Dict(minmax(triout.segmentlist[1, s], triout.segmentlist[2, s]) => triout.segmentmarkerlist[s]
                           for s in 1:numberofsegments(triout))
            @test markers == Dict((1, 2) => 1, (2, 3) => 2, (3, 4) => 3, (1, 4) => 4)
        end
    end

    @testset "unit square, pqQ and second order, pqo2Q (test_o2)" begin
        triin = TriangulateIO(; pointlist = square, segmentlist = square_segments,
                                segmentmarkerlist = Cint[1, 2, 3, 4])
        let
            triout, _ = triangulate("pqQ", triin)
            check_mesh(triout; area = 1.0)
            @test triout.pointlist == square
            @test size(triout.trianglelist) == (3, 2)
        end
        let
            triout, _ = triangulate("pqo2Q", triin)
            check_mesh(triout; area = 1.0)
            p, t = triout.pointlist, triout.trianglelist
            @test size(t) == (6, 2)
            @test numberofpoints(triout) == 9
            @test p[:, 1:4] == square
            # Node 3+i is the midpoint of the edge opposite corner i.
            @test all(p[:, t[3 + i, k]] ≈ (p[:, t[mod1(i + 1, 3), k]] + p[:, t[mod1(i + 2, 3), k]]) / 2
                      for k in 1:2, i in 1:3)
            @test Set(t[4:6, :]) == Set(5:9)
        end
    end

    x = [1.9 1.2 1.5 1.6 1.3 1.9 1.2 1.4 1.1 1.0]
    y = [1.5 1.4 1.7 1.2 1.3 1.9 2.0 1.9 1.5 1.0]
    z = [1.7 1.0 1.1 1.6 2.0 1.8 1.7 1.8 1.7 1.5]
    # Triangle 1.6's Delaunay triangulation of these points (test_pointattributelist); it is
    # unique (no four points cocircular), so the set is exact in any element order.
    delaunay = Cint[10 5 7 2 2 9 2 4 8 8 6 8 3;
                    5 10 9 9 3 7 5 1 3 9 3 6 5;
                    2 4 8 10 9 10 3 3 6 3 1 7 4]

    @testset "point attributes, Q and Qa0.05 (test_pointattributelist)" begin
        pointset = TriangulateIO(; pointlist = [x; y])
        pointset.pointattributelist = z
        triout, vorout = triangulate("Q", pointset)
        check_mesh(triout)
        hull_area = sum(triangle_areas(triout))
        @test triout.pointlist == [x; y]
        @test triout.pointattributelist == z
        @test triangle_set(triout) == Set(canonical(delaunay[:, k]...) for k in axes(delaunay, 2))
        @test isempty(vorout.pointlist) && isempty(vorout.edgelist)

        let
            triout, _ = triangulate("Qa0.05", pointset)
            # Triangle 1.6 splits the hull edge 10-7 at its midpoint, which is point 9's
            # position (up to 2^-53), leaving two flat triangles: tolerated, as Triangle's own.
            check_mesh(triout; area = hull_area, allow_flat = true)
            @test numberofpoints(triout) > 10         # Triangle 1.6: 16 points
            @test triout.pointlist[:, 1:10] == [x; y]
            @test size(triout.pointattributelist) == (1, numberofpoints(triout))
            @test triout.pointattributelist[:, 1:10] == z
            @test all(isfinite, triout.pointattributelist)
            @test maximum(triangle_areas(triout)) <= 0.05 * (1 + 1e-12)
        end
    end

    @testset "Voronoi diagram, vQ, and convex hull segments, cQ (example_pointsets)" begin
        points = TriangulateIO(; pointlist = [x; y])
        triout, vorout = triangulate("vQ", points)
        ntriangles = numberoftriangles(triout)
        nedges = numberofpoints(triout) + ntriangles - 1      # Euler, all points used
        nrays = 2 * nedges - 3 * ntriangles                    # one per convex hull edge
        @test size(vorout.pointlist) == (2, ntriangles)
        @test size(vorout.edgelist) == (2, nedges) && numberofedges(vorout) == nedges
        @test size(vorout.normlist) == (2, nedges)
        @test count(==(-1), vorout.edgelist[2, :]) == nrays
        @test all(e -> 1 <= vorout.edgelist[1, e] <= ntriangles, 1:nedges)
        @test all(e -> vorout.edgelist[2, e] == -1 ? vorout.normlist[:, e] != [0.0, 0.0] :
                                                   vorout.normlist[:, e] == [0.0, 0.0], 1:nedges)
        # Voronoi vertex k is the circumcentre of triangle k.
        circumcentres = all(1:ntriangles) do k
            c = vorout.pointlist[:, k]
            d = [hypot((c - triout.pointlist[:, triout.trianglelist[i, k]])...) for i in 1:3]
            isapprox(d[1], d[2]; rtol = 1e-9) && isapprox(d[1], d[3]; rtol = 1e-9)
        end
        @test circumcentres

        hull, _ = triangulate("cQ", points)
        directed = check_mesh(hull)
        @test numberofsegments(hull) == nrays
        # A hull segment has a triangle on one side only.
        @test all(s -> haskey(directed, (hull.segmentlist[1, s], hull.segmentlist[2, s])) ⊻
                       haskey(directed, (hull.segmentlist[2, s], hull.segmentlist[1, s])), 1:numberofsegments(hull))
        @test all(==(1), hull.segmentmarkerlist)
    end

    diamond = TriangulateIO(; pointlist = Cdouble[1 0 -1 0; 0 1 0 -1],
                              segmentlist = Cint[1 2 3 4; 2 3 4 1])

    @testset "triunsuitable!" begin
        calls = Ref(0)
        counting = (x1, y1, x2, y2, x3, y3, area) -> (calls[] += 1; false)
        @test triunsuitable!(counting) === nothing
        @test calls[] == 1                   # check_signature tried it once
        @test_throws ArgumentError triunsuitable!((args...) -> "yes")
        @test_throws ArgumentError triunsuitable!((args...) -> 0.5)      # no exact Cint
        @test triunsuitable!((args...) -> 1.0) === nothing               # Cint(1.0) == 1
        @test triunsuitable!((args...) -> Int8(0)) === nothing
        @test triunsuitable!(counting; check_signature = false) === nothing
        triangulate("Q", diamond)            # no `u`: the test is never called
        @test calls[] == 1
        @test triunsuitable!(nothing) === nothing
    end

    @testset "u: the test decides refinement, per call and per task" begin
        # The arguments are org, dest, apex (counterclockwise) and the area: check they agree.
        seen = Ref(0)
        consistent = Ref(true)
        small = function (x1, y1, x2, y2, x3, y3, area)
            seen[] += 1
            twice = (x2 - x1) * (y3 - y1) - (y2 - y1) * (x3 - x1)
            longest = max(hypot(x2 - x1, y2 - y1), hypot(x3 - x2, y3 - y2), hypot(x1 - x3, y1 - y3))
            consistent[] &= area > 0 && abs(area - twice / 2) <= 1e-12 * longest^2
            return area > 0.01
        end
        let
            triout, _ = triangulate("quQ", diamond; unsuitable = small)
            check_mesh(triout; area = 2.0)
            @test seen[] > 0
            @test consistent[]
            @test maximum(triangle_areas(triout)) <= 0.01 * (1 + 1e-12)
        end
        let
            # Two tasks mesh at once with different tests set by triunsuitable!; each call
            # must see its own task's test only.
            bound(limit, counter) = (x1, y1, x2, y2, x3, y3, area) -> (counter[] += 1; area > limit)
            coarse_calls, fine_calls = Ref(0), Ref(0)   # each touched by one task only
            function mesh(limit, counter)
                triunsuitable!(bound(limit, counter); check_signature = false)
                return triangulate("quQ", diamond)[1]
            end
            coarse = Threads.@spawn mesh(0.1, coarse_calls)
            fine = Threads.@spawn mesh(0.005, fine_calls)
            coarse_mesh, fine_mesh = fetch(coarse), fetch(fine)
            @test maximum(triangle_areas(coarse_mesh)) <= 0.1 * (1 + 1e-12)
            @test maximum(triangle_areas(fine_mesh)) <= 0.005 * (1 + 1e-12)
            @test numberoftriangles(fine_mesh) > numberoftriangles(coarse_mesh)
            @test coarse_calls[] > 0 && fine_calls[] > 0
        end
    end

    @testset "the test's result converts to Cint, as in Triangulate.jl" begin
        triout, _ = triangulate("quQ", diamond; unsuitable = (x1, y1, x2, y2, x3, y3, area) -> area > 0.05 ? 1.0 : 0.0)
        check_mesh(triout; area = 2.0)
        @test maximum(triangle_areas(triout)) <= 0.05 * (1 + 1e-12)
        @test_throws InexactError triangulate("quQ", diamond; unsuitable = (args...) -> 0.5)
    end

    @testset "an exception in the test stops refinement and is rethrown" begin
        failing = (args...) -> throw(StopMeshing())
        err = try
            triangulate("quQ", diamond; unsuitable = failing)
            nothing
        catch e
            e
        end
        @test err isa StopMeshing
    end

    @testset "show and z" begin
        text = sprint(show, diamond)
        @test occursin("pointlist", text) && occursin("segmentlist", text)
        @test !occursin("holelist", text)
        # `z` is accepted (Triangulate.jl passes it on) and indices stay 1-based.
        zmesh, _ = triangulate("pzQ", diamond)
        plain, _ = triangulate("pQ", diamond)
        @test triangle_set(zmesh) == triangle_set(plain)
        @test minimum(zmesh.trianglelist) == 1 && maximum(zmesh.trianglelist) == numberofpoints(zmesh)
        @test minimum(zmesh.segmentlist) == 1
    end
end
