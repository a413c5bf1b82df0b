# Which triangle-rs library this session calls, opened on first use.
#
# The library is resolved at run time (not with a `const` path in `ccall((:sym, lib), ...)`),
# so that the environment variable can be changed without recompiling the package: the entry
# points are looked up once with `dlsym` and called through their addresses.

const LIBRARY_ENV = "TRIANGLE_RS_LIBRARY"
const LIBRARY_PREFERENCE = "libtriangle_rs_path"

library_file_name() = Sys.iswindows() ? "triangle_rs.dll" : "libtriangle_rs." * Libdl.dlext

# This package lives in `julia/` of the triangle-rs repository, next to cargo's `target/`.
default_library_path() =
    normpath(joinpath(@__DIR__, "..", "..", "target", "release", library_file_name()))

"""
    TriangleRS.library_path() -> String

The triangle-rs shared library this session uses, first found of:
1. the environment variable `TRIANGLE_RS_LIBRARY` (if set and not empty);
2. the preference `libtriangle_rs_path` of this package (`LocalPreferences.toml`, see
   [`TriangleRS.set_library_path!`](@ref));
3. the repository's release build, `target/release/libtriangle_rs.so` (`.dylib`, or
   `triangle_rs.dll` on Windows), built by `cargo build --release --lib`.

The library is opened on the first triangulation; changing these afterwards needs a restart.
"""
function library_path()
    from_env = get(ENV, LIBRARY_ENV, "")
    isempty(from_env) || return from_env
    from_preference = @load_preference(LIBRARY_PREFERENCE, nothing)
    from_preference === nothing || return String(from_preference)
    return default_library_path()
end

"""
    TriangleRS.set_library_path!(path)
    TriangleRS.set_library_path!(nothing)

Stores `path` as the preference `libtriangle_rs_path` in the active project's
`LocalPreferences.toml` (or removes it with `nothing`). Takes effect in the next session, or
in this one if no triangulation has run yet.
"""
function set_library_path!(path::Union{AbstractString,Nothing})
    if path === nothing
        @delete_preferences!(LIBRARY_PREFERENCE)
    else
        isfile(path) || throw(ArgumentError("no file at $(repr(path))"))
        @set_preferences!(LIBRARY_PREFERENCE => String(abspath(path)))
    end
    return nothing
end

# The opened library and the addresses of the entry points this package calls.
struct Library
    path::String
    handle::Ptr{Cvoid}
    triangulate_reentrant::Ptr{Cvoid}
    triangulate_last_error::Ptr{Cvoid}
    trifree::Ptr{Cvoid}
end

const LOADED = Ref{Union{Library,Nothing}}(nothing)
const LOADING = ReentrantLock()

function open_library(path::String)
    handle = Libdl.dlopen(path, Libdl.RTLD_LAZY | Libdl.RTLD_LOCAL; throw_error = false)
    if handle === nothing
        error("""
            TriangleRS cannot open the triangle-rs library at $(repr(path)).
            Build it with `cargo build --release --lib` in the triangle-rs repository, or point
            TriangleRS at it with the environment variable $LIBRARY_ENV or with
            `TriangleRS.set_library_path!(path)`.""")
    end
    return Library(
        path,
        handle,
        Libdl.dlsym(handle, :triangulate_reentrant),
        Libdl.dlsym(handle, :triangulate_last_error),
        Libdl.dlsym(handle, :trifree),
    )
end

# The library, opened once per session (under a lock: tasks on several threads may race here).
function library()::Library
    return lock(LOADING) do
        loaded = LOADED[]
        if loaded === nothing
            loaded = open_library(library_path())
            LOADED[] = loaded
        end
        loaded
    end
end

# A precompiled image must not carry a handle from the session that built it.
__init__() = (LOADED[] = nothing; nothing)

# Frees an array that the library allocated (its `trifree`, which is libc `free`).
trifree(p::Ptr) = ccall(library().trifree, Cvoid, (Ptr{Cvoid},), p)

# The message of the last failed call on this OS thread (the library keeps it thread-local).
function last_error_message(lib::Library)
    p = ccall(lib.triangulate_last_error, Ptr{UInt8}, ())
    return p == C_NULL ? "" : unsafe_string(p)
end
