!> The block operators GMRES works with (kcreep_krylov block_operator_t):
!> the system operator through the FFT operator, the circulant and the strip
!> preconditioners, on the unknowns of the subsystems (kcreep_split), one
!> subsystem per column.
module kcreep_block_operators
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_split, only: subsystem_t, restrict_to, restrict_projected, expand_from, shares_transforms
  use kcreep_fft_operator, only: fft_operator_t, apply_fft_operator
  use kcreep_preconditioner, only: strip_preconditioner_t, apply_strip_preconditioner
  use kcreep_circulant_preconditioner, only: circulant_preconditioner_t, apply_circulant_preconditioner
  use kcreep_krylov, only: block_operator_t
  use kcreep_patch, only: patch_t, part_patch
  use kcreep_assembly, only: operator_table_t, slip_weight
  implicit none
  private
  public :: expanded_block_t, fft_block_t, circulant_block_t, strip_block_t

  !> GMRES works on the unknowns of the subsystems (system_split), one
  !> subsystem per column, padded with zeros to the longest: a y-symmetric
  !> patch thus needs half-length Krylov vectors and half the preconditioner
  !> work. An operator on the full grid sees the expanded full traction
  !> (mirror cells included) and its result is restricted back.
  type, abstract, extends(block_operator_t) :: expanded_block_t
    type(subsystem_t), allocatable :: subs(:)
    integer, allocatable :: sub_of(:)     !< subsystem of each column
    integer :: n = 0
    !> Work arrays of whole tractions, kept between steps (allocating them
    !> anew at every step cost as much kernel time as the FFTs took)
    real(real64), allocatable :: full(:, :), zfull(:, :)
  contains
    procedure :: apply => apply_expanded
    procedure(full_apply), deferred :: apply_full
  end type expanded_block_t

  abstract interface
    !> z(:, k) = M full(:, k) on whole tractions (px(1:n), py(1:n)).
    subroutine full_apply(self, full, z)
      import :: expanded_block_t, real64
      class(expanded_block_t), intent(inout) :: self
      real(real64), intent(in) :: full(:, :)
      real(real64), intent(out) :: z(:, :)
    end subroutine full_apply
  end interface

  !> The system operator, applied with FFTs.
  type, extends(expanded_block_t) :: fft_block_t
    type(fft_operator_t) :: op
  contains
    procedure :: apply_full => apply_fft_full
  end type fft_block_t

  !> The circulant preconditioner on the full grid. On a blended patch
  !> (kcreep_assembly slip_weight) it runs on the core, the cells at least
  !> core_fraction inside, and each other cell is solved from its own row,
  !> its own coefficient and that of the cell ahead in x, from the leading
  !> edge back (set_edge).
  type, extends(expanded_block_t) :: circulant_block_t
    type(circulant_preconditioner_t) :: p
    logical, allocatable :: in_core(:)     !< (n) a blended patch's cell is in the core
    integer, allocatable :: core(:)        !< the core's cells (patch cell numbers)
    integer, allocatable :: ahead(:)       !< (n) the patch cell next in x, 0 none
    real(real64), allocatable :: ahead_coefficient(:, :)   !< (n, 2) the x and y rows' coefficient of it
    real(real64) :: own(2) = 0             !< the rows' own-cell coefficient (x, y)
  contains
    procedure :: apply_full => apply_circulant_full
    procedure :: set_edge, core_patch
  end type circulant_block_t

  !> The blended patch's core: cells at least this much inside (or the most
  !> inside, on a patch with none). The circulant inverse of a core of cells
  !> at least half inside took 29-70 GMRES steps per level on the S1002
  !> flange strips, of cells at least 0.9 inside 11-18, as many as the
  !> staircase's levels (docs/wheel_rail_checks.md, "The blended edge").
  real(real64), parameter :: core_fraction = 0.9_real64

  !> The strip preconditioner on the representative cells (their mirror
  !> rows have the same blocks, so the reduced preconditioner is the full
  !> one restricted).
  type, extends(block_operator_t) :: strip_block_t
    type(strip_preconditioner_t) :: p
    type(subsystem_t), allocatable :: subs(:)
    integer, allocatable :: sub_of(:)
    integer :: n = 0
  contains
    procedure :: apply => apply_strip_block
  end type strip_block_t

contains

  !> The block through the full-grid operator. Columns of the two parity
  !> classes of a y-symmetric patch (kcreep_split shares_transforms) go in
  !> pairs through one full vector: the operator keeps each class's
  !> parities, so the result comes apart by projection, and the three load
  !> cases cost the transforms of two (xi with eta, phi alone).
  subroutine apply_expanded(self, x, y, columns)
    class(expanded_block_t), intent(inout) :: self
    real(real64), intent(in) :: x(:, :)
    real(real64), intent(out) :: y(:, :)
    integer, intent(in) :: columns(:)
    integer :: c, m, nv, nf, f
    integer :: vector_of(size(x, 2))   !< full vector of each column
    logical :: shared(size(x, 2))      !< its vector holds another column too
    nv = size(x, 2)
    call pair_columns(self%subs, self%sub_of(columns), vector_of, shared)
    nf = maxval(vector_of)
    if (allocated(self%full)) then
      if (size(self%full, 1) /= 2 * self%n .or. size(self%full, 2) < nf) deallocate (self%full, self%zfull)
    end if
    if (.not. allocated(self%full)) allocate (self%full(2 * self%n, nf), self%zfull(2 * self%n, nf))
    ! vectors on threads: each is its own copy, so the result does not depend on them
    !$omp parallel do private(c, m) schedule(static)
    do f = 1, nf
      self%full(:, f) = 0
      do c = 1, nv
        if (vector_of(c) /= f) cycle
        m = self%subs(self%sub_of(columns(c)))%m
        call expand_from(self%subs(self%sub_of(columns(c))), self%n, x(1:m, c), self%full(:, f))
      end do
    end do
    !$omp end parallel do
    call self%apply_full(self%full(:, 1:nf), self%zfull(:, 1:nf))
    !$omp parallel do private(m) schedule(static)
    do c = 1, nv
      y(:, c) = 0
      m = self%subs(self%sub_of(columns(c)))%m
      if (shared(c)) then
        call restrict_projected(self%subs(self%sub_of(columns(c))), self%n, self%zfull(:, vector_of(c)), y(1:m, c))
      else
        call restrict_to(self%subs(self%sub_of(columns(c))), self%n, self%zfull(:, vector_of(c)), y(1:m, c))
      end if
    end do
    !$omp end parallel do
  end subroutine apply_expanded

  !> Full vectors for the columns of a block (subsystem subs(sub(c)) for
  !> column c): each column shares one with the next unpaired column of the
  !> other parity class (in column order); the rest have one each.
  pure subroutine pair_columns(subs, sub, vector_of, shared)
    type(subsystem_t), intent(in) :: subs(:)
    integer, intent(in) :: sub(:)
    integer, intent(out) :: vector_of(:)
    logical, intent(out) :: shared(:)
    integer :: c, d, nf
    vector_of = 0
    shared = .false.
    nf = 0
    do c = 1, size(sub)
      if (vector_of(c) > 0) cycle
      nf = nf + 1
      vector_of(c) = nf
      do d = c + 1, size(sub)
        if (vector_of(d) == 0 .and. shares_transforms(subs(sub(c)), subs(sub(d)))) then
          vector_of(d) = nf
          shared([c, d]) = .true.
          exit
        end if
      end do
    end do
  end subroutine pair_columns

  subroutine apply_fft_full(self, full, z)
    class(fft_block_t), intent(inout) :: self
    real(real64), intent(in) :: full(:, :)
    real(real64), intent(out) :: z(:, :)
    call apply_fft_operator(self%op, full, z)
  end subroutine apply_fft_full

  subroutine apply_circulant_full(self, full, z)
    class(circulant_block_t), intent(inout) :: self
    real(real64), intent(in) :: full(:, :)
    real(real64), intent(out) :: z(:, :)
    real(real64), allocatable :: core_full(:, :), core_z(:, :)
    integer :: v, n, m, k
    if (.not. allocated(self%in_core)) then
      call apply_circulant_preconditioner(self%p, full, z)
      return
    end if
    n = self%n
    m = size(self%core)
    allocate (core_full(2 * m, size(full, 2)), core_z(2 * m, size(full, 2)))
    do v = 1, size(full, 2)
      core_full(:, v) = full([self%core, n + self%core], v)
    end do
    call apply_circulant_preconditioner(self%p, core_full, core_z)
    do v = 1, size(full, 2)
      z(:, v) = 0
      z([self%core, n + self%core], v) = core_z(:, v)
      ! the edge cells, from the leading edge (largest x) back: the cell ahead is known
      do k = n, 1, -1
        if (self%in_core(k)) cycle
        z(k, v) = full(k, v)
        z(n + k, v) = full(n + k, v)
        if (self%ahead(k) > 0) then
          z(k, v) = z(k, v) - self%ahead_coefficient(k, 1) * z(self%ahead(k), v)
          z(n + k, v) = z(n + k, v) - self%ahead_coefficient(k, 2) * z(n + self%ahead(k), v)
        end if
        z(k, v) = z(k, v) / self%own(1)
        z(n + k, v) = z(n + k, v) / self%own(2)
      end do
    end do
  end subroutine apply_circulant_full

  !> The blended patch's core and edge (none for another patch). The
  !> circulant inverse is built for G = 1, so the edge's coefficients are
  !> taken in the same units.
  subroutine set_edge(self, patch, table)
    class(circulant_block_t), intent(inout) :: self
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    real(real64), allocatable :: w(:)
    integer :: k, n
    if (allocated(self%in_core)) deallocate (self%in_core, self%core, self%ahead, self%ahead_coefficient)
    if (.not. allocated(patch%fraction)) return
    n = patch%n
    self%in_core = patch%fraction >= min(core_fraction, maxval(patch%fraction))
    self%core = pack([(k, k=1, n)], self%in_core)
    self%ahead = patch%cell_ahead()
    allocate (self%ahead_coefficient(n, 2))
    self%ahead_coefficient = 0
    if (patch%mx > 1) then
      w = slip_weight(patch%fraction)
      self%ahead_coefficient(:, 1) = w * table%xx(-1, 0) * table%g
      self%ahead_coefficient(:, 2) = w * table%yy(-1, 0) * table%g
    end if
    self%own = [table%xx(0, 0), table%yy(0, 0)] * table%g
  end subroutine set_edge

  !> The cells the circulant inverse runs on: the core of a blended patch
  !> (after set_edge), else the patch itself.
  function core_patch(self, patch) result(core)
    class(circulant_block_t), intent(in) :: self
    type(patch_t), intent(in) :: patch
    type(patch_t) :: core
    if (.not. allocated(self%in_core)) then
      core = patch
      return
    end if
    core = part_patch(patch, self%in_core)
    deallocate (core%fraction)
  end function core_patch

  subroutine apply_strip_block(self, x, y, columns)
    class(strip_block_t), intent(inout) :: self
    real(real64), intent(in) :: x(:, :)
    real(real64), intent(out) :: y(:, :)
    integer, intent(in) :: columns(:)
    real(real64), allocatable :: full(:, :), zfull(:, :)
    integer :: c, u
    allocate (full(2 * self%n, size(x, 2)), zfull(2 * self%n, size(x, 2)))
    full = 0
    do c = 1, size(x, 2)
      associate (s => self%subs(self%sub_of(columns(c))))
        do u = 1, s%m
          full(s%comp(u) * self%n + s%cell(u), c) = x(u, c)
        end do
      end associate
    end do
    call apply_strip_preconditioner(self%p, full, zfull)
    y = 0
    do c = 1, size(x, 2)
      associate (s => self%subs(self%sub_of(columns(c))))
        call restrict_to(s, self%n, zfull(:, c), y(1:s%m, c))
      end associate
    end do
  end subroutine apply_strip_block

end module kcreep_block_operators
