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

  !> The circulant preconditioner on the full grid.
  type, extends(expanded_block_t) :: circulant_block_t
    type(circulant_preconditioner_t) :: p
  contains
    procedure :: apply_full => apply_circulant_full
  end type circulant_block_t

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
    call apply_circulant_preconditioner(self%p, full, z)
  end subroutine apply_circulant_full

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
