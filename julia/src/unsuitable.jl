# The user's `u` test (Triangle's `triunsuitable`), passed to the library per call.
#
# Triangulate.jl stores the test in a C global (`triunsuitable_callback`), so two tasks that
# mesh with different tests at the same time use each other's test. Here each call hands the
# library a C trampoline plus a pointer to an `UnsuitableCall` object (`user_data` of
# `triangulate_reentrant`), and the trampoline calls that object's test: no global state is
# read during a call.

const TASK_KEY = :TriangleRS_triunsuitable

# The test set by the latest `triunsuitable!` in any task: used by tasks that never set one,
# so that code written for Triangulate.jl (set the test, then spawn work) keeps working.
const DEFAULT_TEST = Ref{Any}(nothing)
const DEFAULT_TEST_LOCK = ReentrantLock()

"""
    triunsuitable!(unsuitable; check_signature = true)
    triunsuitable!(nothing)

Sets the test that Triangle's `u` switch applies to every triangle during refinement:
`unsuitable(x1, y1, x2, y2, x3, y3, area)` receives the triangle's corners (counterclockwise)
and its area and returns `true` if the triangle must be split. It is called only after the
`a` area tests have passed. `nothing` removes the test: `u` then applies Triangle's built-in
test, as the C library does with no test (see the README of triangle-rs).

Unlike Triangulate.jl's, the setting is safe across tasks and threads: it applies to the
calling task, and it is also the default for tasks that never call `triunsuitable!`. Each
`triangulate` call reads it once at its start. To be independent of any setting, pass the test
per call: `triangulate(switches, triin; unsuitable = f)`.

If the test throws, refinement is stopped and `triangulate` rethrows the exception.

The result may be anything that converts to `Cint` (as in Triangulate.jl, which passes
`Cint(unsuitable(...))` to Triangle): `true`/`false`, an integer, `1.0`; non-zero means split.
With `check_signature`, `unsuitable` is called once on a sample triangle and its result must
convert to `Cint` (otherwise an `ArgumentError`); a result that does not convert during a
refinement stops it, and `triangulate` rethrows the conversion error.

```julia
triunsuitable!((x1, y1, x2, y2, x3, y3, area) -> area > 0.01 * (1 + x1^2))
triout, _ = triangulate("pquQ", triin)
```
"""
function triunsuitable!(unsuitable; check_signature::Bool = true)
    if unsuitable !== nothing && check_signature
        verdict = unsuitable(0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.5)
        converts = try
            unsuitable_verdict(verdict)
            true
        catch err
            err isa Union{MethodError,InexactError} || rethrow()
            false
        end
        converts || throw(ArgumentError(
            "the unsuitable test must return a value that converts to Cint (e.g. a Bool), " *
            "but returned $(repr(verdict)) for the triangle (0,0), (1,0), (0,1) with area 0.5"))
    end
    task_local_storage(TASK_KEY, unsuitable)
    lock(DEFAULT_TEST_LOCK) do
        DEFAULT_TEST[] = unsuitable
    end
    return nothing
end

# The test that a call from the current task uses: its own setting, else the default.
function current_unsuitable()
    storage = task_local_storage()
    haskey(storage, TASK_KEY) && return storage[TASK_KEY]
    return lock(() -> DEFAULT_TEST[], DEFAULT_TEST_LOCK)
end

# One call's state, handed to the library as `user_data`. Mutable, so that it has a stable
# address (`pointer_from_objref`); the caller keeps it alive with `GC.@preserve`.
mutable struct UnsuitableCall
    # `f(x1, y1, x2, y2, x3, y3, area)`, or `nothing` for no test.
    test::Any
    # The library's `cancel` flag: set when the test throws, so that refinement stops.
    cancel::Base.RefValue{Cint}
    # What the test threw, rethrown once the library has returned.
    failure::Any
end

UnsuitableCall(test) = UnsuitableCall(test, Ref{Cint}(0), nothing)

# Triangulate.jl's rule: the result converted to `Cint`, non-zero meaning unsuitable.
unsuitable_verdict(verdict) = convert(Cint, verdict) != Cint(0)

# Called by the library (from the thread that called `triangulate_reentrant`) with the
# triangle's origin, destination and apex, its area, and our `user_data`. A Julia exception
# must not unwind through the library's frames, so it is caught here and the call cancelled.
function unsuitable_trampoline(
        org_x::Cdouble, org_y::Cdouble,
        dest_x::Cdouble, dest_y::Cdouble,
        apex_x::Cdouble, apex_y::Cdouble,
        area::Cdouble,
        user_data::Ptr{Cvoid},
    )::Cint
    call = unsafe_pointer_to_objref(user_data)::UnsuitableCall
    call.failure === nothing || return Cint(0)
    try
        verdict = call.test(org_x, org_y, dest_x, dest_y, apex_x, apex_y, area)
        return unsuitable_verdict(verdict) ? Cint(1) : Cint(0)
    catch err
        call.failure = err
        call.cancel[] = Cint(1)
        return Cint(0)
    end
end

# The C function pointer of the trampoline: `int (*)(double x7, void *user_data)`.
unsuitable_trampoline_pointer() = @cfunction(
    unsuitable_trampoline,
    Cint,
    (Cdouble, Cdouble, Cdouble, Cdouble, Cdouble, Cdouble, Cdouble, Ptr{Cvoid})
)
