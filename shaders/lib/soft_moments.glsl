// Soft shadows on summed-area tables of the moments (src/shadows/summed.rs): variance soft
// shadow maps (Yang et al. 2010, on Lauritzen's summed-area variance shadow maps, GPU Gems 3
// ch. 8) and moment soft shadow maps (Peters et al. 2016). Like PCSS (pcss.glsl,
// whose lightPenumbra, pcssDistance and pcssPenumbra they share) a blocker search, then a
// filter as wide as the penumbra; but each stage reads the table a fixed number of times
// whatever its width (by default 25 integer reads, the corners of 4 x 4 cells), the same
// cost at 2 texels as at 64.

// The box's half width in texels: at least 1, two texels wide, three read (a kernel that
// vanishes at contact brings back acne; PCSS's least disc is a texel's radius), at most 64
// (src/engine/summed_area.rs: SAT_MAX_BOX = 2 x 64 + 2).
const float SOFT_MIN_TEXELS = 1.0;
const float SOFT_MAX_TEXELS = 64.0;
// Fixed-point units per unit of a moment (src/engine/summed_area.rs: SAT_SCALE).
const float SAT_SCALE_F = 131072.0;
// The least variance of msm-soft's search cells and single texels, whose settings hold none
// (vssm's is its min_variance).
const float SOFT_SEARCH_VARIANCE = 1e-6;
// A disc light's penumbra across a straight edge is the share of the disc past a line,
// whose spread along the edge's normal has variance R^2 / 4 for a disc of radius R; a box
// of half width a has a^2 / 3. The box of the same spread: a = R sqrt(3) / 2.
const float SOFT_BOX_OF_DISC = 0.8660254;
// From this half width on (texels) the filter box is split in cells snapped to whole
// texels; below, its texels are read one by one (softBox).
const float SOFT_CELL_TEXELS = 4.0;
// The most cells a side of a stage's box (settings soft_search_cells, soft_filter_cells):
// the corners' arrays are sized from it. Each call passes its own count as a literal, which
// the compiler folds, so a lattice of n cells costs (n + 1)^2 reads and no more.
const int SOFT_MAX_CELLS = 4;

// A box's half width in texels for a penumbra's half width in uv, within the bounds.
vec2 softHalf(vec2 halfUv, vec2 size)
{
    return clamp(halfUv * size, vec2(SOFT_MIN_TEXELS), vec2(SOFT_MAX_TEXELS));
}

// The receiver's depth as a plane in the map, its slope (depth per uv) from the screen-space
// derivatives of (uv, z), as PCSS's receiver-plane bias (pcss.glsl): none where the
// 2 x 2 solve is singular, at most PCSS_MAX_SLOPE.
vec2 softReceiverSlope(vec3 projCoords)
{
    vec3 ddx = dFdx(projCoords);
    vec3 ddy = dFdy(projCoords);
    float det = ddx.x * ddy.y - ddx.y * ddy.x;
    vec2 slope = abs(det) > 1e-14
        ? vec2(ddx.z * ddy.y - ddx.y * ddy.z, ddx.x * ddy.z - ddy.x * ddx.z) / det
        : vec2(0.0);
    return clamp(slope, -PCSS_MAX_SLOPE, PCSS_MAX_SLOPE);
}

// What softBox sums over a box's cells: the blockers (share, depth sum), vssm's bound
// or msm-soft's 4MSM visibility.
const int SOFT_SEARCH = 0;
const int SOFT_VSSM = 1;
const int SOFT_MSM = 2;

// One cell's part, `kind` as softBox', for the cell's mean moments `m` and the receiver
// plane's depth `ti` at its centre. A cell of blockers over a planar receiver has
// mean = p t + (1 - p) blockers (Yang et al. 2010): the search's part is (1 - p, blockers
// (1 - p)). `settings`: vssm's (min variance, bleed reduction); msm-soft's (alpha, toward).
// A `single` texel's moments are one depth: msm-soft compares it by Chebyshev's bound with
// the least variance, a hard test (the moment bias would blur a depth known exactly).
vec2 softCell(int kind, vec4 m, float ti, bool single, float minVariance, vec2 settings,
              vec4 toward)
{
    if (kind == SOFT_SEARCH) {
        float unoccluded = chebyshevUpperBound(m.xy, ti, minVariance);
        return vec2(1.0 - unoccluded, max(m.x - unoccluded * ti, 0.0));
    }
    if (kind == SOFT_VSSM) {
        float bound = chebyshevUpperBound(m.xy, ti, settings.x);
        return vec2(reduceLightBleeding(bound, settings.y), 0.0);
    }
    if (single) {
        return vec2(chebyshevUpperBound(m.xy, ti, SOFT_SEARCH_VARIANCE), 0.0);
    }
    return vec2(momentVisibility(m, ti, settings.x, toward), 0.0);
}

// The cells of a lattice of the table's corners, `cells` a side (`xs`, `ys`: table indices,
// the corner after texel xs[i]), (cells + 1)^2 reads: each cell's mean moments are tested
// against the receiver plane at the cell's centre, `t + slope . offset` (a tilted receiver
// mixed into one box's variance reads lit where it is not, and passes for a blocker: VSSM's
// subdivision of a non-planar receiver, here always, with the receiver's plane); returns
// the cells' parts (softCell) weighted by the share of each cell inside the box lo..hi
// (texels of the map), over the box's area. Read row by row, so that no array is indexed
// by a loop the compiler may keep. Each corner is read at its texel's centre through the
// sampler (NEAREST): llvmpipe's texelFetch on an integer texture cost twice a lookup.
vec2 softLattice(usampler2D table, int cells, int xs[SOFT_MAX_CELLS + 1],
                 int ys[SOFT_MAX_CELLS + 1], vec2 lo, vec2 hi, vec2 centre, vec2 size, float t,
                 vec2 slope, int kind, float minVariance, vec2 settings, vec4 toward)
{
    float wx[SOFT_MAX_CELLS];
    for (int i = 0; i < cells; ++i) {
        wx[i] = max(min(hi.x, float(xs[i + 1] + 1)) - max(lo.x, float(xs[i] + 1)), 0.0);
    }
    vec2 sum = vec2(0.0);
    float total = 0.0;
    uvec4 above[SOFT_MAX_CELLS + 1];
    for (int j = 0; j <= cells; ++j) {
        uvec4 row[SOFT_MAX_CELLS + 1];
        for (int i = 0; i <= cells; ++i) {
            row[i] = textureLod(table, (vec2(xs[i], ys[j]) + 0.5) / size, 0.0);
        }
        if (j > 0) {
            float wy = max(min(hi.y, float(ys[j] + 1)) - max(lo.y, float(ys[j - 1] + 1)), 0.0);
            for (int i = 0; i < cells; ++i) {
                float area = float((xs[i + 1] - xs[i]) * (ys[j] - ys[j - 1]));
                uvec4 cell = row[i + 1] - row[i] - above[i + 1] + above[i];
                vec4 m = vec4(cell) / (SAT_SCALE_F * max(area, 1.0));
                vec2 offset = 0.5 * vec2(xs[i] + xs[i + 1], ys[j] + ys[j - 1]) + 1.0 - centre;
                float ti = t + dot(slope, offset / size);
                float w = area > 0.0 ? wx[i] * wy : 0.0;
                sum += w * softCell(kind, m, ti, area == 1.0, minVariance, settings,
                                    toward);
                total += w;
            }
        }
        above = row;
    }
    return sum / max(total, 1e-6);
}

// The box centre +- reach over one lattice of `cells` x `cells` cells of the table
// (softLattice), (cells + 1)^2 reads whichever the box. A wide box (`narrow` false) is split
// in cells of whole texels, its corners snapped to the texels': a texel is a small part of
// it. A narrow box (under SOFT_CELL_TEXELS either side) is read over `cells` x `cells`
// blocks of whole texels from its first texel, each block a texel (at 4 cells, a box up to 3
// texels wide) or a few: each block's
// own moments, exact to the table's unit, against the receiver's plane, weighted by the
// part of the box it covers. A single texel's variance is nothing but the least one, so
// the test is PCF's comparison, texel by texel, at the box's width: one box's bound over
// caster and receiver together leaks light. The narrow box is clamped to the map (its edge
// texels read past it, as a clamped texture's), two texels wide at least.
// `narrow` chooses the corners, not the code: llvmpipe runs both sides of a branch that
// differs between pixels, and each side would read the whole lattice.
vec2 softBox(usampler2D table, int cells, vec2 centre, vec2 reach, vec2 size, bool narrow,
             float t, vec2 slope, int kind, float minVariance, vec2 settings, vec4 toward)
{
    vec2 nlo = clamp(centre - reach, vec2(1.0), size - 3.0);
    vec2 nhi = clamp(centre + reach, nlo + 2.0, size - 1.0);
    vec2 first = floor(nlo);
    vec2 block = max(ceil((floor(nhi) - first + 1.0) / float(cells)), 1.0);
    int xs[SOFT_MAX_CELLS + 1];
    int ys[SOFT_MAX_CELLS + 1];
    for (int i = 0; i <= cells; ++i) {
        vec2 cell = floor(centre - reach + reach * (2.0 / float(cells) * float(i)) + 0.5);
        vec2 corner = clamp(narrow ? first + block * float(i) : cell, vec2(1.0), size - 1.0);
        xs[i] = int(corner.x) - 1;
        ys[i] = int(corner.y) - 1;
    }
    vec2 lo = narrow ? nlo : vec2(xs[0], ys[0]) + 1.0;
    vec2 hi = narrow ? nhi : vec2(xs[cells], ys[cells]) + 1.0;
    return softLattice(table, cells, xs, ys, lo, hi, centre, size, t, slope, kind, minVariance,
                       settings, toward);
}

// The blocker search at a fixed cost: the search box's cells (softBox) by Chebyshev's
// bound, each against the receiver plane (one planar box over the whole region took the
// tilted floor for blockers, and drew penumbrae too wide); the blockers' mean depth is the
// cells' blocker sums over their shares. t where no cell holds blockers.
float softBlockerSearch(usampler2D table, int cells, vec2 centre, vec2 reach, vec2 size,
                        float t, vec2 slope, float minVariance)
{
    vec2 found = softBox(table, cells, centre, reach, size, false, t, slope, SOFT_SEARCH,
                         minVariance, vec2(0.0), vec4(0.0));
    return found.x > 1e-5 ? clamp(found.y / found.x, 0.0, t) : t;
}

// vssm's filter: Chebyshev's bound with the light-bleeding reduction over the box
// (softBox), its cells from SOFT_CELL_TEXELS on, its texels below (weighted by the box's
// fractional corners, so a narrow kernel moves smoothly).
float vssmFilter(usampler2D table, int cells, vec2 centre, vec2 reach, vec2 size, float t,
                 vec2 slope, float minVariance, float bleedReduction)
{
    bool narrow = min(reach.x, reach.y) < SOFT_CELL_TEXELS;
    return softBox(table, cells, centre, reach, size, narrow, t, slope, SOFT_VSSM, 0.0,
                   vec2(minVariance, bleedReduction), vec4(0.0)).x;
}

// msm-soft's filter: the same with the 4MSM reconstruction (moment bias `alpha` toward
// `toward`).
float msmSoftFilter(usampler2D table, int cells, vec2 centre, vec2 reach, vec2 size, float t,
                    vec2 slope, float alpha, vec4 toward)
{
    bool narrow = min(reach.x, reach.y) < SOFT_CELL_TEXELS;
    return softBox(table, cells, centre, reach, size, narrow, t, slope, SOFT_MSM, 0.0,
                   vec2(alpha, 0.0), toward).x;
}

// The filter's half width in texels, from the blocker search: the penumbra of blockers at
// depth zb for a receiver at z (pcssPenumbra), times SOFT_BOX_OF_DISC, within the bounds.
vec2 softFilterHalf(float z, float zb, vec4 light, bool perspective, vec2 size)
{
    float dr = pcssDistance(z, light, perspective);
    float db = pcssDistance(zb, light, perspective);
    return softHalf(SOFT_BOX_OF_DISC * pcssPenumbra(dr, db, light, perspective), size);
}

// The search region's half width in texels: the light's disc seen from the receiver
// through the near plane (as PCSS's).
vec2 softSearchHalf(float z, vec4 light, bool perspective, vec2 size)
{
    float dr = pcssDistance(z, light, perspective);
    return softHalf(pcssPenumbra(dr, light.z, light, perspective), size);
}

// Variance soft shadow maps: (z, z^2) over the search box, Chebyshev's bound for the
// blockers' share and depth, then the bound over a box as wide as their penumbra, with
// the light-bleeding reduction. `searchCells`, `filterCells`: each stage's cells a side.
float vssm(usampler2D table, vec4 position, float bias, vec2 texel, vec4 light,
           int searchCells, int filterCells, float minVariance, float bleedReduction,
           bool perspective, bool borderLit, bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    vec2 size = 1.0 / texel;
    vec2 centre = projCoords.xy * size;
    float t = projCoords.z - bias;
    vec2 slope = softReceiverSlope(projCoords);
    float zb = softBlockerSearch(table, searchCells, centre,
                                 softSearchHalf(t, light, perspective, size), size, t, slope,
                                 minVariance);
    vec2 reach = softFilterHalf(t, zb, light, perspective, size);
    float lit = vssmFilter(table, filterCells, centre, reach, size, t, slope, minVariance,
                           bleedReduction);
    return outsideLit(projCoords, lit, borderLit, beyondFarLit);
}

// Moment soft shadow maps: the same with four moments, the Hamburger 4MSM reconstruction
// for both the blockers' share and the filter, the moment bias `alpha` toward `toward`.
float msmSoft(usampler2D table, vec4 position, float bias, vec2 texel, vec4 light,
              int searchCells, int filterCells, float alpha, vec4 toward, bool perspective,
              bool borderLit, bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    vec2 size = 1.0 / texel;
    vec2 centre = projCoords.xy * size;
    float t = projCoords.z - bias;
    vec2 slope = softReceiverSlope(projCoords);
    float zb = softBlockerSearch(table, searchCells, centre,
                                 softSearchHalf(t, light, perspective, size), size, t, slope,
                                 SOFT_SEARCH_VARIANCE);
    vec2 reach = softFilterHalf(t, zb, light, perspective, size);
    float lit = msmSoftFilter(table, filterCells, centre, reach, size, t, slope, alpha, toward);
    return outsideLit(projCoords, lit, borderLit, beyondFarLit);
}
