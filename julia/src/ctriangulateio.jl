# Triangle's `struct triangulateio`, field for field, and the raw call.
#
# Not part of the public interface (as in Triangulate.jl, `TriangleRS.CTriangulateIO` and the
# four-argument `TriangleRS.triangulate` exist for callers that manage the C arrays themselves).

# `struct triangulateio` (168 bytes on 64-bit systems). Julia lays out the fields of this
# struct as C does (natural alignment), and a mutable struct passed as `Ref{CTriangulateIO}`
# is passed by address, so the library's writes land in this object.
mutable struct CTriangulateIO
    pointlist::Ptr{Cdouble}
    pointattributelist::Ptr{Cdouble}
    pointmarkerlist::Ptr{Cint}
    numberofpoints::Cint
    numberofpointattributes::Cint

    trianglelist::Ptr{Cint}
    triangleattributelist::Ptr{Cdouble}
    trianglearealist::Ptr{Cdouble}
    neighborlist::Ptr{Cint}
    numberoftriangles::Cint
    numberofcorners::Cint
    numberoftriangleattributes::Cint

    segmentlist::Ptr{Cint}
    segmentmarkerlist::Ptr{Cint}
    numberofsegments::Cint

    holelist::Ptr{Cdouble}
    numberofholes::Cint

    regionlist::Ptr{Cdouble}
    numberofregions::Cint

    edgelist::Ptr{Cint}
    edgemarkerlist::Ptr{Cint}
    normlist::Ptr{Cdouble}
    numberofedges::Cint
end

# Every pointer NULL and every count 0: what Triangle expects of `out` and `vorout`.
CTriangulateIO() = CTriangulateIO(
    C_NULL, C_NULL, C_NULL, 0, 0,
    C_NULL, C_NULL, C_NULL, C_NULL, 0, 0, 0,
    C_NULL, C_NULL, 0,
    C_NULL, 0,
    C_NULL, 0,
    C_NULL, C_NULL, C_NULL, 0,
)

# The array fields the library may allocate in `out`/`vorout`. `holelist` and `regionlist` are
# not among them: the library copies the input's pointers there (Triangle's rule), so freeing
# them would free the caller's input.
const ALLOCATED_FIELDS = (
    :pointlist, :pointattributelist, :pointmarkerlist,
    :trianglelist, :triangleattributelist, :trianglearealist, :neighborlist,
    :segmentlist, :segmentmarkerlist,
    :edgelist, :edgemarkerlist, :normlist,
)

# Frees what the library allocated in `ctio` (after an error, or for arrays nobody takes) and
# clears those fields.
function free_allocated!(ctio::CTriangulateIO)
    for name in ALLOCATED_FIELDS
        p = getfield(ctio, name)
        if p != C_NULL
            trifree(p)
            setproperty!(ctio, name, C_NULL) # converts C_NULL to the field's pointer type
        end
    end
    return ctio
end

# Runs `triangulate_reentrant` with `call`'s test; returns the library's code (0 = success)
# and, on failure, its message. The caller keeps every array that `ctio_in` points to alive.
function triangulate_reentrant!(
        switches::String,
        ctio_in::CTriangulateIO,
        ctio_out::CTriangulateIO,
        vor_out::CTriangulateIO,
        call::UnsuitableCall,
    )
    lib = library()
    callback = call.test === nothing ? C_NULL : unsuitable_trampoline_pointer()
    rc = GC.@preserve call begin
        user_data = call.test === nothing ? C_NULL : pointer_from_objref(call)
        ccall(
            lib.triangulate_reentrant,
            Cint,
            (
                Cstring,                 # switches, NUL-terminated
                Ref{CTriangulateIO},     # in
                Ref{CTriangulateIO},     # out
                Ref{CTriangulateIO},     # vorout (never NULL, as in Triangulate.jl)
                Ptr{Cvoid},              # int (*unsuitable)(double x7, void *user_data)
                Ptr{Cvoid},              # user_data
                Ref{Cint},               # const int *cancel
            ),
            switches, ctio_in, ctio_out, vor_out, callback, user_data, call.cancel
        )
    end
    # Read at once: the message is kept per OS thread until the next call on that thread.
    message = rc == 0 ? "" : last_error_message(lib)
    return rc, message
end

"""
    TriangleRS.triangulate(switches, ctio_in, ctio_out, vor_out; unsuitable) -> Cint

The raw call, as in Triangulate.jl: triangulates `ctio_in` into `ctio_out` and `vor_out`
and returns 0 on success, non-zero on error (never exits). The caller keeps the arrays of
`ctio_in` alive and frees what the library allocated in `ctio_out`/`vor_out` with libc `free`,
except `holelist`/`regionlist`, which alias `ctio_in`'s. The `u` test is the current task's
(see [`triunsuitable!`](@ref)) unless given; if it throws, the exception is rethrown after the
call (the outputs are still the caller's to free).
"""
function triangulate(
        switches::AbstractString,
        ctio_in::CTriangulateIO,
        ctio_out::CTriangulateIO,
        vor_out::CTriangulateIO;
        unsuitable = current_unsuitable(),
    )
    call = UnsuitableCall(unsuitable)
    rc, _ = triangulate_reentrant!(String(switches), ctio_in, ctio_out, vor_out, call)
    call.failure === nothing || throw(call.failure)
    return rc
end
