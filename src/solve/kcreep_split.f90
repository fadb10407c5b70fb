!> Splitting the full-adhesion system into the independent smaller systems
!> the scene allows, so that only what is needed is factorised.
!>
!> Mirror symmetry in y: with the mirror M (cell (ix, iy) <-> (ix, my+1-iy)),
!> the kernel's xx and yy parts are even in y and its xy part is odd, so
!> the operator commutes with the map (px, py) -> (px o M, -py o M). Each
!> right-hand side has a parity: xi gives (px even, py odd); eta and phi give
!> (px odd, py even) (rhs_x = -y is odd, rhs_y = x + shift is even). The
!> solution keeps the parity of its right-hand side, so it is fixed by its
!> values on one half of the patch: the columns of a cell and its mirror add
!> (even) or subtract (odd), and an odd component vanishes on a middle row.
!> Each parity class is a system of about n unknowns instead of 2n: two
!> factorisations of size n cost a quarter of one of size 2n.
!> nu = 0: the xy coefficients vanish and px, py decouple (xi and eta then
!> need only one component each; phi needs both).
module kcreep_split
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: operator_table_t, n_load_cases, slip_weight
  implicit none
  private
  public :: subsystem_t, plan_subsystems, assemble_subsystem, restrict_to, restrict_projected, expand_from
  public :: shares_transforms

  integer, parameter :: all_cells = 0, even = 1, odd = -1

  !> One independent system: its unknowns are (component, representative cell);
  !> a representative's mirror partner carries the same value times sign.
  type :: subsystem_t
    character(len=:), allocatable :: label
    logical :: serves(n_load_cases) = .false.  !< load cases that need this system
    integer :: m = 0                           !< unknowns
    integer, allocatable :: comp(:)            !< 0: px, 1: py
    integer, allocatable :: cell(:)            !< representative cell
    integer, allocatable :: partner(:)         !< its mirror, 0 when none (or itself)
    real(real64), allocatable :: sign(:)       !< +1 even, -1 odd
    !> The parities of the displacement its tractions give under the mirror:
    !> +1 (ux even, uy odd: 'px even, py odd', 'px even'), -1 (ux odd, uy
    !> even: 'px odd, py even', 'px odd', 'py even'), 0 no mirror used. The
    !> operator keeps them, so fields of classes +1 and -1 added on one grid
    !> come apart again by parity (shares_transforms).
    integer :: parity_class = 0
  end type subsystem_t

contains

  !> The systems to solve for the requested load cases. decouple (default
  !> true): split px from py when nu = 0 (smaller dense factorisations; the
  !> iterative path keeps them together, see solve_iterative). sizes_only
  !> (default false): label, serves and m only, without the cell lists (a
  !> memory check of a grid too large to plan in full: 3 million cells take
  !> 0.5 GB and 1 s to plan).
  function plan_subsystems(patch, nu, split, requested, decouple, sizes_only) result(subs)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: nu
    logical, intent(in) :: split, requested(n_load_cases)
    logical, intent(in), optional :: decouple, sizes_only
    type(subsystem_t), allocatable :: subs(:)
    type(subsystem_t) :: candidates(3)
    integer :: nc, i
    logical :: symmetric, decoupled

    symmetric = split .and. patch%mirror_symmetric_in_y()
    decoupled = split .and. nu == 0
    if (present(decouple)) decoupled = decoupled .and. decouple
    if (symmetric .and. decoupled) then
      candidates(1) = build('px even', [0], [even], [.true., .false., .false.])
      candidates(2) = build('px odd', [0], [odd], [.false., .false., .true.])
      candidates(3) = build('py even', [1], [even], [.false., .true., .true.])
      nc = 3
    else if (symmetric) then
      candidates(1) = build('px even, py odd', [0, 1], [even, odd], [.true., .false., .false.])
      candidates(2) = build('px odd, py even', [0, 1], [odd, even], [.false., .true., .true.])
      nc = 2
    else if (decoupled) then
      candidates(1) = build('px', [0], [all_cells], [.true., .false., .true.])
      candidates(2) = build('py', [1], [all_cells], [.false., .true., .true.])
      nc = 2
    else
      candidates(1) = build('px, py', [0, 1], [all_cells, all_cells], [.true., .true., .true.])
      nc = 1
    end if
    subs = pack(candidates(1:nc), [(any(candidates(i)%serves .and. requested), i=1, nc)])

  contains

    function build(label, comps, parities, serves) result(s)
      character(len=*), intent(in) :: label
      integer, intent(in) :: comps(:), parities(:)
      logical, intent(in) :: serves(n_load_cases)
      type(subsystem_t) :: s
      integer, allocatable :: cell_of(:, :)
      integer :: k, p, mirror_iy
      logical :: keep(patch%n)
      integer :: partner(patch%n)
      integer, parameter :: none(0) = [integer ::]
      s%label = label
      s%serves = serves
      ! px even or py odd: class +1; px odd or py even: class -1 (parity_class)
      if (parities(1) /= all_cells) s%parity_class = merge(1, -1, (comps(1) == 0) .eqv. (parities(1) == even))
      if (present(sizes_only)) then
        if (sizes_only) then
          s%m = 0
          do p = 1, size(comps)
            if (parities(p) == all_cells) then
              s%m = s%m + patch%n
            else
              s%m = s%m + count(2 * patch%iy(1:patch%n) < patch%my + 1 .or. &
                                (2 * patch%iy(1:patch%n) == patch%my + 1 .and. parities(p) == even))
            end if
          end do
          return
        end if
      end if
      allocate (cell_of(patch%mx, patch%my))
      cell_of = 0
      do k = 1, patch%n
        cell_of(patch%ix(k), patch%iy(k)) = k
      end do
      s%comp = none
      s%cell = none
      s%partner = none
      allocate (s%sign(0))
      do p = 1, size(comps)
        do k = 1, patch%n
          mirror_iy = patch%my + 1 - patch%iy(k)
          if (parities(p) == all_cells) then
            keep(k) = .true.
            partner(k) = 0
          else
            ! lower half, plus the middle row for an even component
            keep(k) = patch%iy(k) < mirror_iy .or. (patch%iy(k) == mirror_iy .and. parities(p) == even)
            partner(k) = merge(cell_of(patch%ix(k), mirror_iy), 0, patch%iy(k) < mirror_iy)
          end if
        end do
        s%comp = [s%comp, spread(comps(p), 1, count(keep))]
        s%cell = [s%cell, pack([(k, k=1, patch%n)], keep)]
        s%partner = [s%partner, pack(partner, keep)]
        s%sign = [s%sign, spread(real(merge(1, parities(p), parities(p) == all_cells), real64), 1, count(keep))]
      end do
      s%m = size(s%cell)
    end function build

  end function plan_subsystems

  !> The dense matrix of a subsystem: column v is A times the full traction
  !> that unknown v stands for (its cell, plus sign times its mirror), at the
  !> representative rows.
  subroutine assemble_subsystem(patch, table, s, a)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    type(subsystem_t), intent(in) :: s
    real(real64), intent(out) :: a(:, :)   !< (m, m)
    integer, allocatable :: run_first(:), run_last(:)
    integer :: v, u, r, nr, m, ixv, iyv, iyp, di, dj, djp, l
    logical :: new_run
    real(real64) :: w

    ! Runs: consecutive unknowns of one component on consecutive cells of one
    ! grid row. Their coefficients are a contiguous slice of the offset table,
    ! so a column is filled by a few vector copies instead of m lookups.
    m = s%m
    allocate (run_first(m), run_last(m))
    nr = 0
    do u = 1, m
      new_run = u == 1
      if (.not. new_run) new_run = s%comp(u) /= s%comp(u - 1) .or. &
                                   patch%iy(s%cell(u)) /= patch%iy(s%cell(u - 1)) .or. &
                                   patch%ix(s%cell(u)) /= patch%ix(s%cell(u - 1)) + 1
      if (new_run) then
        nr = nr + 1
        run_first(nr) = u
      end if
      run_last(nr) = u
    end do

    !$omp parallel do private(ixv, iyv, iyp, r, di, dj, djp, l) schedule(static)
    do v = 1, m
      ixv = patch%ix(s%cell(v))
      iyv = patch%iy(s%cell(v))
      iyp = iyv
      if (s%partner(v) > 0) iyp = patch%iy(s%partner(v))
      do r = 1, nr
        associate (u1 => run_first(r), u2 => run_last(r))
          di = patch%ix(s%cell(u1)) - ixv
          dj = patch%iy(s%cell(u1)) - iyv
          djp = patch%iy(s%cell(u1)) - iyp
          l = u2 - u1
          ! (every value the copy needs is passed: a host-associated variable
          ! would be the shared one, not this thread's private copy)
          if (s%comp(u1) == 0 .and. s%comp(v) == 0) then
            call fill_run(table%xx, di, dj, djp, l, s%partner(v) > 0, s%sign(v), a(u1:u2, v))
          else if (s%comp(u1) == 1 .and. s%comp(v) == 1) then
            call fill_run(table%yy, di, dj, djp, l, s%partner(v) > 0, s%sign(v), a(u1:u2, v))
          else
            call fill_run(table%xy, di, dj, djp, l, s%partner(v) > 0, s%sign(v), a(u1:u2, v))
          end if
        end associate
      end do
    end do
    !$omp end parallel do
    ! a blended patch's rows (kcreep_assembly slip_weight)
    if (.not. allocated(patch%fraction)) return
    do u = 1, m
      w = slip_weight(patch%fraction(s%cell(u)))
      a(u, :) = w * a(u, :)
      a(u, u) = a(u, u) + (1 - w) * merge(table%xx(0, 0), table%yy(0, 0), s%comp(u) == 0)
    end do
  end subroutine assemble_subsystem

  !> col = t(di:di+l, dj) [+ sign t(di:di+l, djp) for a mirrored column];
  !> t is the offset table with its lower bounds shifted to 1.
  pure subroutine fill_run(t, di, dj, djp, l, mirrored, sign, col)
    real(real64), intent(in) :: t(:, :)
    integer, intent(in) :: di, dj, djp, l
    logical, intent(in) :: mirrored
    real(real64), intent(in) :: sign
    real(real64), intent(out) :: col(:)
    integer :: cx, cy
    cx = (size(t, 1) + 1) / 2    ! position of offset 0
    cy = (size(t, 2) + 1) / 2
    if (mirrored) then
      col = t(cx + di:cx + di + l, cy + dj) + sign * t(cx + di:cx + di + l, cy + djp)
    else
      col = t(cx + di:cx + di + l, cy + dj)
    end if
  end subroutine fill_run

  !> The subsystem's entries of a full vector (px(1:n), py(1:n)).
  pure subroutine restrict_to(s, n, full, part)
    type(subsystem_t), intent(in) :: s
    integer, intent(in) :: n
    real(real64), intent(in) :: full(:)
    real(real64), intent(out) :: part(:)
    part = full(s%comp * n + s%cell)
  end subroutine restrict_to

  !> The subsystem's entries of a full vector that holds, besides this
  !> subsystem's field, one of the other parity class: each entry is
  !> projected on the subsystem's parity, (value + sign x mirror value) / 2.
  !> On a middle row (no partner) a field of the other class is zero.
  pure subroutine restrict_projected(s, n, full, part)
    type(subsystem_t), intent(in) :: s
    integer, intent(in) :: n
    real(real64), intent(in) :: full(:)
    real(real64), intent(out) :: part(:)
    integer :: u
    do u = 1, s%m
      if (s%partner(u) > 0) then
        part(u) = (full(s%comp(u) * n + s%cell(u)) + s%sign(u) * full(s%comp(u) * n + s%partner(u))) / 2
      else
        part(u) = full(s%comp(u) * n + s%cell(u))
      end if
    end do
  end subroutine restrict_projected

  !> Whether the fields of two subsystems can share one full-grid vector
  !> through a parity-preserving operator (the system operator, the
  !> circulant preconditioner): one of each parity class.
  elemental logical function shares_transforms(s, t)
    type(subsystem_t), intent(in) :: s, t
    shares_transforms = s%parity_class * t%parity_class == -1
  end function shares_transforms

  !> Add the full traction a subsystem solution stands for to full.
  pure subroutine expand_from(s, n, part, full)
    type(subsystem_t), intent(in) :: s
    integer, intent(in) :: n
    real(real64), intent(in) :: part(:)
    real(real64), intent(inout) :: full(:)
    integer :: u
    do u = 1, s%m
      full(s%comp(u) * n + s%cell(u)) = full(s%comp(u) * n + s%cell(u)) + part(u)
      if (s%partner(u) > 0) full(s%comp(u) * n + s%partner(u)) = &
        full(s%comp(u) * n + s%partner(u)) + s%sign(u) * part(u)
    end do
  end subroutine expand_from

end module kcreep_split
