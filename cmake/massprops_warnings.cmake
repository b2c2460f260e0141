# massprops_set_warnings(target): the project's warning set, private to each target.
function(massprops_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
endfunction()

# massprops_set_floating_point(target): the floating-point rules that results depend on, set on
# every target that computes. Results must be the same bits on every run and every thread count;
# -ffp-contract=off keeps the compiler from contracting a*b+c into FMAs differently in different
# inlining contexts.
function(massprops_set_floating_point target)
  target_compile_options(${target} PRIVATE -ffp-contract=off)
  # Shared libraries: calls within a library may still be inlined (nobody interposes them).
  target_compile_options(${target} PRIVATE -fno-semantic-interposition)
endfunction()
