!> FASTSIM (Kalker 1982) with Coulomb friction on the patch's own grid.
!>
!> Simplified theory: the elastic displacement difference is u = L p, with
!> one flexibility L per traction component. In steady rolling (leading edge
!> at +x, material moving toward -x) the adhesion condition
!> du/dx = w, w = (xi - phi y, eta + phi x), makes the traction grow
!> linearly in the rigid slip from zero at the leading edge of each strip
!> segment:  dp/dx = w / L.  Where |p| would exceed the traction bound
!> g = mu pn, the cell slips and p = g p*/|p*| (p* the adhesion predictor).
!>
!> Discretisation: each grid row (strip) is marched from +x to -x; every
!> separate segment of a strip (run of patch cells) starts traction-free at
!> its own leading edge x_l = x_k + dx/2. The traction of a cell is its
!> cell average. For a rigid slip linear in x (as here) the cell averages of
!> the adhesion solution obey exactly
!>   first cell of a segment:  p_k = -(h/L) w(x_k + h/3)
!>   next cells:               p_k = p_(k+1) - (2h/L) w(x_k + h)
!> (h = dx/2), so that in full adhesion the forces are I1/L1 xi, I1/L2 eta,
!> I3/L3 phi with the cell-exact strip integrals of kcreep_fastsim: with the
!> exact L1 L2 L3 FASTSIM reproduces f11, f22, f23 to round-off at small
!> creepage. The traction bound is applied to the cell averages.
!>
!> Flexibility of combined creepages:
!>  - weighted (Kalker 1982): one L for all components,
!>    L = (|xi| L1 + |eta| L2 + c |phi| L3) / sqrt(xi^2 + eta^2 + c^2 phi^2),
!>    c = sqrt(area/pi) (= sqrt(ab) for an ellipse);
!>  - separate: each creepage term with its own flexibility,
!>    dp_x/dx = xi/L1 - phi y/L3,  dp_y/dx = eta/L2 + phi x/L3.
!>    This keeps the linear theory's ratio of the creepage components'
!>    effects in combined creepage (the single L of the weighted rule cannot),
!>    but a slipping cell keeps the predictor's direction, so at full slip F
!>    points along (xi/L1 - phi y/L3, eta/L2 + phi x/L3), not along the slip;
!>  - aligned (the default of the program): with one flexibility per
!>    component for the creepage point, D = diag(Dx, Dy),
!>    Dx = (|xi| L1 + c |phi| L3)/(|xi| + c |phi|),
!>    Dy = (|eta| L2 + c |phi| L3)/(|eta| + c |phi|) (the terms weighted as
!>    the weighted rule weights them; the L by their size):
!>    adhesion: dp_x/dx = xi/L1 - phi y/Dx, dp_y/dx = eta/L2 + phi x/|L3|
!>    (the separate rule, but the longitudinal slip of spin with Dx: L3 for
!>    pure spin, toward L1 as xi dominates, as u_x = L1 p_x would have it;
!>    both spin terms with |L3|: where L3 < 0 a negative L3 on one term and
!>    |L3| on the other turned pure spin's tractions against each other,
!>    up to 19 % of mu Fn worse than plain FASTSIM on an L-shaped patch);
!>    slip: the traction opposes the slip of the simplified theory u = D p,
!>    D (p - p_up) + step w, so p = (D + lambda)^-1 (D p_up - step w) with
!>    |p| = g (one root, Newton on the secular equation 1/g - 1/|p(lambda)|).
!>    Small creepage: f11, f22, f23 exact as with the separate rule (where
!>    L3 < 0: -f23, a near-cancelled f23 no positive L3 reproduces); pure
!>    creepage: Kalker's FASTSIM with |L3|; full slip: F along the rigid slip w, as in
!>    the exact solution (docs/fastsim.md, "Against the exact solver": the study against the
!>    exact rolling solver).
!>
!> Forces: Fx = sum px dA, Fy = sum py dA, Mz = sum (x py - y px) dA,
!> Fn = sum pn dA; adhesion = fraction of the patch cells in adhesion.
!> Everything here is pure: arrays in, numbers out.
module kcreep_fastsim_forces
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  implicit none
  private
  public :: fastsim_forces, fastsim_result_t, weighted_flexibility
  public :: flexibility_weighted, flexibility_separate, flexibility_aligned, flexibility_rule_name, spin_x_flexibility
  public :: flexibility_rule_of
  public :: cell_outside, cell_adhesion, cell_slip, mask_strip_integrals

  integer, parameter :: flexibility_weighted = 1, flexibility_separate = 2, flexibility_aligned = 3
  !> stick/slip map values (CONTACT's IGS: 0 exterior, 1 adhesion, 2 slip)
  integer, parameter :: cell_outside = 0, cell_adhesion = 1, cell_slip = 2

  type :: fastsim_result_t
    real(real64) :: fx = 0, fy = 0, mz = 0, fn = 0
    real(real64) :: adhesion = 1          !< fraction of the patch area in adhesion
  end type fastsim_result_t

contains

  !> Name of a flexibility rule ('weighted', 'separate', 'aligned'); '' when unknown.
  pure function flexibility_rule_name(rule) result(name)
    integer, intent(in) :: rule
    character(len=:), allocatable :: name
    select case (rule)
    case (flexibility_weighted)
      name = 'weighted'
    case (flexibility_separate)
      name = 'separate'
    case (flexibility_aligned)
      name = 'aligned'
    case default
      name = ''
    end select
  end function flexibility_rule_name

  !> The rule of a name (flexibility_rule_name's inverse); 0 when unknown.
  pure integer function flexibility_rule_of(name) result(rule)
    character(len=*), intent(in) :: name
    select case (name)
    case ('weighted')
      rule = flexibility_weighted
    case ('separate')
      rule = flexibility_separate
    case ('aligned')
      rule = flexibility_aligned
    case default
      rule = 0
    end select
  end function flexibility_rule_of

  !> Kalker's single flexibility for the creepage (xi, eta, phi); L1 at zero creepage.
  pure real(real64) function weighted_flexibility(flex, creep, c_len) result(l)
    real(real64), intent(in) :: flex(3), creep(3), c_len
    real(real64) :: norm
    norm = sqrt(creep(1)**2 + creep(2)**2 + (c_len * creep(3))**2)
    if (norm > 0) then
      l = (abs(creep(1)) * flex(1) + abs(creep(2)) * flex(2) + c_len * abs(creep(3)) * flex(3)) / norm
    else
      l = flex(1)
    end if
  end function weighted_flexibility

  !> Creep forces of one creepage point.
  !>  inside(mx, my): cells of the patch; pn(mx, my): normal pressure (>= 0, read on patch cells);
  !>  cell (ix, iy) has its centre at (x0 + (ix-1) dx, y0 + (iy-1) dy);
  !>  flex = (L1, L2, L3); mu: friction coefficient; creep = (xi, eta, phi);
  !>  c_len: length of the weighted and aligned rules (sqrt(area/pi)); rule: flexibility_weighted,
  !>  _separate or _aligned.
  !> Optional: px, py (mx, my) the cell tractions (0 outside), state (mx, my) the stick/slip map.
  pure subroutine fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, creep, c_len, rule, &
                                 res, px, py, state, flex_spin_x)
    logical, intent(in) :: inside(:, :)
    real(real64), intent(in) :: pn(:, :), dx, dy, x0, y0, flex(3), mu, creep(3), c_len
    integer, intent(in) :: rule
    type(fastsim_result_t), intent(out) :: res
    real(real64), intent(out), optional :: px(:, :), py(:, :)
    integer, intent(out), optional :: state(:, :)
    real(real64), intent(in), optional :: flex_spin_x   !< L of the -phi y term (default separate L3, aligned Dx)
    real(real64) :: h, da, x, y, tx, ty, gx, gy, bound, mag, step, xe
    real(real64) :: rx, ry, sx, sy, fx, fy, mz, fn
    real(real64) :: inv1, inv2, inv3, slip_flex(2)
    integer :: ix, iy, mx, my, n_cells, n_adhesion, s
    logical :: leading

    mx = size(inside, 1)
    my = size(inside, 2)
    h = dx / 2
    da = dx * dy
    if (rule == flexibility_weighted) then
      inv1 = 1 / weighted_flexibility(flex, creep, c_len)
      inv2 = inv1
      inv3 = inv1
    else
      inv1 = 1 / flex(1)
      inv2 = 1 / flex(2)
      inv3 = 1 / flex(3)
    end if
    ! d p / d x per unit distance: (sx - spin_x * y, sy + spin_y * x)
    sx = creep(1) * inv1
    sy = creep(2) * inv2
    rx = creep(3) * inv3
    ry = creep(3) * inv3
    if (rule == flexibility_aligned) then
      slip_flex = aligned_slip_flexibility(flex, creep, c_len)
      rx = creep(3) / slip_flex(1)
      ry = creep(3) / abs(flex(3))          ! L3 by its size, as in Dx and D (pure spin: |L3| in both terms)
    end if
    if (rule /= flexibility_weighted .and. present(flex_spin_x)) rx = creep(3) / flex_spin_x

    fx = 0; fy = 0; mz = 0; fn = 0
    n_cells = 0; n_adhesion = 0
    if (present(px)) px = 0
    if (present(py)) py = 0
    if (present(state)) state = cell_outside
    do iy = 1, my
      y = y0 + (iy - 1) * dy
      tx = 0; ty = 0
      do ix = mx, 1, -1                       ! from the leading edge (+x) downstream
        if (.not. inside(ix, iy)) cycle
        x = x0 + (ix - 1) * dx
        leading = leading_cell(inside(:, iy), ix)
        if (leading) then
          tx = 0; ty = 0
          step = h
          xe = x + h / 3
        else
          step = dx
          xe = x + h
        end if
        ! adhesion predictor: p* = p_upstream - step * dp/dx at xe
        gx = tx - step * (sx - rx * y)
        gy = ty - step * (sy + ry * xe)
        bound = mu * max(pn(ix, iy), 0.0_real64)
        mag = sqrt(gx**2 + gy**2)
        if (mag > bound) then
          if (rule == flexibility_aligned) then
            ! slip of u = D p: p = (D + lambda)^-1 (D p_up - step w), |p| = g
            call aligned_slip(slip_flex, tx - step * (creep(1) - creep(3) * y) / slip_flex(1), &
                              ty - step * (creep(2) + creep(3) * xe) / slip_flex(2), bound, gx, gy)
          else if (mag > 0) then
            gx = gx * (bound / mag)
            gy = gy * (bound / mag)
          end if
          s = cell_slip
        else
          s = cell_adhesion
          n_adhesion = n_adhesion + 1
        end if
        tx = gx; ty = gy
        n_cells = n_cells + 1
        fx = fx + tx
        fy = fy + ty
        mz = mz + x * ty - y * tx
        fn = fn + max(pn(ix, iy), 0.0_real64)
        if (present(px)) px(ix, iy) = tx
        if (present(py)) py(ix, iy) = ty
        if (present(state)) state(ix, iy) = s
      end do
    end do
    res%fx = fx * da
    res%fy = fy * da
    res%mz = mz * da
    res%fn = fn * da
    if (n_cells > 0) then
      res%adhesion = real(n_adhesion, real64) / n_cells
    else
      res%adhesion = 0
    end if
  end subroutine fastsim_forces

  !> (Dx, Dy) of the aligned rule's slip for the creepage (xi, eta, phi): each the mean of the
  !> flexibilities of the terms of its component, weighted as the weighted rule weights them,
  !> Dx = (|xi| L1 + c |phi| L3)/(|xi| + c |phi|), Dy = (|eta| L2 + c |phi| L3)/(|eta| + c |phi|)
  !> (L1, L2 where the component has no creepage). The L enter by their size: L3 = I3/f23 is
  !> negative on a patch whose f23 and I3 differ in sign (a crescent with its horns toward +x,
  !> spun about a point near its centroid), and D must stay positive.
  pure function aligned_slip_flexibility(flex, creep, c_len) result(d)
    real(real64), intent(in) :: flex(3), creep(3), c_len
    real(real64) :: d(2)
    real(real64) :: w
    w = c_len * abs(creep(3))
    d = abs(flex(1:2))
    if (abs(creep(1)) + w > 0) d(1) = (abs(creep(1)) * abs(flex(1)) + w * abs(flex(3))) / (abs(creep(1)) + w)
    if (abs(creep(2)) + w > 0) d(2) = (abs(creep(2)) * abs(flex(2)) + w * abs(flex(3))) / (abs(creep(2)) + w)
  end function aligned_slip_flexibility

  !> The traction p on the bound |p| = g nearest to q in the norm Dx px^2 + Dy py^2:
  !> p = (D + lambda)^-1 D q, lambda >= 0 with |p| = g; q itself when |q| <= g. Newton on the
  !> secular equation phi(lambda) = 1/g - 1/|p(lambda)| (convex and decreasing: from a point
  !> below the root the iterates rise monotonically to it). Start: lambda = min(D) (|q|/g - 1),
  !> below the root since |p(lambda)| >= |q| min(D)/(min(D) + lambda), and the root itself when
  !> Dx = Dy. Stop at |p| = g within 1e-13 relative, then p is put on the bound.
  pure subroutine aligned_slip(d, qx, qy, g, px, py)
    real(real64), intent(in) :: d(2), qx, qy, g
    real(real64), intent(out) :: px, py
    real(real64) :: lambda, r, dr, f, step, a1, a2
    integer :: k
    px = qx; py = qy
    r = sqrt(qx**2 + qy**2)
    if (r <= g) return
    if (g <= 0) then
      px = 0; py = 0
      return
    end if
    lambda = minval(d) * (r / g - 1)
    do k = 1, 100
      a1 = 1 / (d(1) + lambda)
      a2 = 1 / (d(2) + lambda)
      px = d(1) * qx * a1
      py = d(2) * qy * a2
      r = sqrt(px**2 + py**2)
      f = 1 / g - 1 / r
      if (abs(r - g) <= 1e-13_real64 * g) exit
      dr = -(px**2 * a1 + py**2 * a2) / r
      step = f * r**2 / dr
      if (.not. (step < 0)) exit            ! no progress left (round-off)
      lambda = lambda - step
    end do
    if (.not. (r > 0)) then                  ! g so small that p underflowed: the radial projection
      px = qx; py = qy
      r = sqrt(qx**2 + qy**2)
    end if
    px = px * (g / r)                        ! on the bound to round-off
    py = py * (g / r)
  end subroutine aligned_slip

  !> Flexibility of the longitudinal spin term (-phi y) under the separate rule, such that the
  !> full-adhesion spin moment is -f33 phi:  Mz = -phi (J3 / L3 + J2 / L4) with
  !> J2 = Int y^2 (x_l - x) dA, J3 = Int x (x_l^2 - x^2)/2 dA (cell-exact); NaN when f33 <= J3/L3.
  pure real(real64) function spin_x_flexibility(inside, dx, dy, x0, y0, l3, f33) result(l4)
    logical, intent(in) :: inside(:, :)
    real(real64), intent(in) :: dx, dy, x0, y0, l3, f33
    real(real64) :: h, x_lead, x, y, j2, j3
    integer :: ix, iy, mx

    mx = size(inside, 1)
    h = dx / 2
    j2 = 0; j3 = 0
    do iy = 1, size(inside, 2)
      y = y0 + (iy - 1) * dy
      x_lead = 0
      do ix = mx, 1, -1
        if (.not. inside(ix, iy)) cycle
        x = x0 + (ix - 1) * dx
        if (leading_cell(inside(:, iy), ix)) x_lead = x + h
        j2 = j2 + (y**2 + dy**2 / 12) * 2 * h * (x_lead - x)
        ! Int x (x_l^2 - x^2)/2 dx over the cell [x - h, x + h]
        j3 = j3 + (x_lead**2 * x * h - (x**3 * h + x * h**3))
      end do
    end do
    j2 = j2 * dy; j3 = j3 * dy
    if (f33 > j3 / l3) then
      l4 = j2 / (f33 - j3 / l3)
    else
      l4 = ieee_value(l4, ieee_quiet_nan)
    end if
  end function spin_x_flexibility

  !> (I1, I3) of the patch: I1 = Int (x_l - x) dA, I3 = Int (x_l^2 - x^2)/2 dA over every strip
  !> segment with leading edge x_l, integrated exactly over the cells (kcreep_fastsim
  !> strip_integrals for a patch_t): FASTSIM's full-adhesion forces are I1 xi / L1, I1 eta / L2,
  !> I3 phi / L3. Per cell of half length h centred at x_k: Int (x_l - x) dx = 2h (x_l - x_k)
  !> and Int (x_l^2 - x^2)/2 dx = h (x_l^2 - x_k^2) - h^3/3.
  pure function mask_strip_integrals(inside, dx, dy, x0) result(moments)
    logical, intent(in) :: inside(:, :)
    real(real64), intent(in) :: dx, dy, x0
    real(real64) :: moments(2)
    real(real64) :: h, x_lead, x
    integer :: ix, iy, mx

    mx = size(inside, 1)
    h = dx / 2
    moments = 0
    do iy = 1, size(inside, 2)
      x_lead = 0
      do ix = mx, 1, -1
        if (.not. inside(ix, iy)) cycle
        x = x0 + (ix - 1) * dx
        if (leading_cell(inside(:, iy), ix)) x_lead = x + h
        moments(1) = moments(1) + 2 * h * (x_lead - x)
        moments(2) = moments(2) + h * (x_lead**2 - x**2) - h**3 / 3
      end do
    end do
    moments = moments * dy
  end function mask_strip_integrals

  !> Whether cell ix of a grid row is the leading (+x) cell of its strip segment: the row's
  !> last cell, or followed by a cell outside the patch (the caller knows ix is inside).
  pure logical function leading_cell(row, ix)
    logical, intent(in) :: row(:)
    integer, intent(in) :: ix
    leading_cell = ix == size(row)
    if (.not. leading_cell) leading_cell = .not. row(ix + 1)
  end function leading_cell

end module kcreep_fastsim_forces
