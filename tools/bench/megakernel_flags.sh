# Sourced from the repository root, once $m names the memograph binary, by the scripts that
# measure the megakernel (the thesis's path tracer: the memoization sweep, its pictures, the
# cache checks, culling): shadingFlags is (--shading megakernel) for a binary whose --shading
# defaults to auto (the wavefront on a GPU), and empty for an older one, which knows no other.
shadingFlags=()
"$m" bench --help 2>&1 | grep -qE -- '--shading (S +auto|auto\|)' && shadingFlags=(--shading megakernel)
