# massprops_set_warnings(target): the project's warning set, private to each target.
function(massprops_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
endfunction()

# Results must be the same bits on every run and every thread count; keep the compiler from
# contracting a*b+c into FMAs differently in different inlining contexts.
add_compile_options(-ffp-contract=off)
