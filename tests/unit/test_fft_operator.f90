!> Unit tests of the FFT operator (kcreep_fft_operator) and the circulant
!> preconditioner's apply.
!>  1. The pruned transforms (rows of the patch, then spectrum columns)
!>     against the direct sum over the operator table (apply_operator): the
!>     same convolution, so equal to rounding; measured 2e-15 to 3e-15 of the
!>     largest entry on these patches, allowed 1e-13.
!>  2. The pruned transforms against the whole-grid 2-D ones: measured
!>     identical (FFTW's 2-D plan for these sizes runs the same row and
!>     column transforms), allowed 1e-14 of the largest entry since FFTW
!>     promises no particular order of operations.
!>  3. With OpenMP: the operator and the preconditioner give bit-identical
!>     results on 1 and on 2 threads. Each thread transforms whole slots with
!>     the same single-threaded plan, and the kernel product and the running
!>     sums have no reductions, so nothing depends on the thread count.
!>  4. Parity (what lets the iterative solver put two load cases through one
!>     set of transforms, kcreep_linear_solve apply_expanded): on a
!>     y-symmetric patch the operator and the preconditioner map a field of
!>     parities (px even, py odd) to displacements of the same parities, and
!>     (px odd, py even) likewise, so the result for the sum of one field of
!>     each class, projected on a class, is that class's own result. The
!>     projection's difference is rounding: allowed 1e-12 of the largest
!>     entry, measured below 1e-15 (printed). Also at nu = 0, where the
!>     iterative path keeps px and py together (plan_subsystems with
!>     decouple = .false.: the two classes, so xi pairs with eta) instead
!>     of the three decoupled systems the dense path factorises.
program test_fft_operator
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t
  use kcreep_patch, only: patch_t, ellipse_patch
  use kcreep_assembly, only: scheme_t, operator_table_t, build_operator_table, apply_operator, n_load_cases
  use kcreep_split, only: subsystem_t, plan_subsystems
  use kcreep_fft_operator, only: fft_operator_t, create_fft_operator, apply_fft_operator, destroy_fft_operator
  use kcreep_circulant_preconditioner, only: circulant_preconditioner_t, build_circulant_preconditioner, &
                                            apply_circulant_preconditioner, destroy_circulant_preconditioner
  !$ use omp_lib, only: omp_set_num_threads, omp_get_max_threads
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t

  ! odd and even grid sizes, a/b away from 1 (mx /= my), and both schemes
  call check_patch(1.0_real64, 1.0_real64, 24, 24, 'backward')
  call check_patch(1.5_real64, 0.6_real64, 37, 15, 'collocation')
  call check_patch(0.4_real64, 1.2_real64, 11, 32, 'backward')
  call check_threads(60)
  call check_parity(1.0_real64, 1.0_real64, 48, 48, 0.3_real64)
  call check_parity(1.3_real64, 0.7_real64, 41, 27, 0.3_real64)
  call check_parity(0.5_real64, 2.0_real64, 30, 121, 0.3_real64)
  call check_parity(1.3_real64, 0.7_real64, 41, 27, 0.0_real64)
  call check_coupled_plan()
  call t%finish()

contains

  subroutine check_patch(a, b, mx, my, scheme_name)
    real(real64), intent(in) :: a, b
    integer, intent(in) :: mx, my
    character(len=*), intent(in) :: scheme_name
    type(status_t) :: st
    type(patch_t) :: patch
    type(scheme_t) :: scheme
    type(operator_table_t) :: table
    type(fft_operator_t) :: pruned, whole
    real(real64), allocatable :: x(:, :), y(:, :), y_whole(:, :), y_direct(:, :)
    character(len=64) :: label
    integer :: v

    write (label, '(i0, a, i0, 1x, a)') mx, ' x ', my, scheme_name
    call ellipse_patch(a, b, mx, my, patch, st)
    scheme%name = scheme_name
    call build_operator_table(patch, scheme, 0.3_real64, 1.0_real64, table)
    call create_fft_operator(patch, table, 3, pruned)
    call create_fft_operator(patch, table, 3, whole, pruned=.false.)
    allocate (x(2 * patch%n, 3), y(2 * patch%n, 3), y_whole(2 * patch%n, 3), y_direct(2 * patch%n, 3))
    call random_number(x)
    x = x - 0.5_real64
    do v = 1, 3
      call apply_operator(patch, table, x(:, v), y_direct(:, v))
    end do
    call apply_fft_operator(pruned, x, y)
    call apply_fft_operator(whole, x, y_whole)
    call t%check(maxval(abs(y - y_direct)) <= 1e-13_real64 * maxval(abs(y_direct)), &
                 trim(label)//': pruned FFT operator = direct sum')
    call t%check(maxval(abs(y - y_whole)) <= 1e-14_real64 * maxval(abs(y_whole)), &
                 trim(label)//': pruned transforms = whole-grid transforms')
    ! a narrower block reuses the slots: the same columns
    call apply_fft_operator(pruned, x(:, 2:2), y_whole(:, 1:1))
    call t%check(all(y_whole(:, 1) == y(:, 2)), trim(label)//': a block of one = that column of the block of three')
    call destroy_fft_operator(pruned)
    call destroy_fft_operator(whole)
  end subroutine check_patch

  subroutine check_threads(m)
    integer, intent(in) :: m
    type(status_t) :: st
    type(patch_t) :: patch
    type(fft_operator_t) :: op
    type(circulant_preconditioner_t) :: prec
    real(real64), allocatable :: x(:, :), y1(:, :), y2(:, :), z1(:, :), z2(:, :)
    integer :: threads

    threads = 0
    !$ threads = omp_get_max_threads()
    if (threads == 0) then
      print '(a)', 'skip thread-count checks: built without OpenMP'
      return
    end if
    call ellipse_patch(1.0_real64, 1.0_real64, m, m, patch, st)
    call backward_operators(patch, 0.25_real64, op, prec)
    allocate (x(2 * patch%n, 3), y1(2 * patch%n, 3), y2(2 * patch%n, 3), z1(2 * patch%n, 3), z2(2 * patch%n, 3))
    call random_number(x)
    !$ call omp_set_num_threads(1)
    call apply_fft_operator(op, x, y1)
    call apply_circulant_preconditioner(prec, x, z1)
    !$ call omp_set_num_threads(2)
    call apply_fft_operator(op, x, y2)
    call apply_circulant_preconditioner(prec, x, z2)
    !$ call omp_set_num_threads(threads)
    call t%check(all(y1 == y2), 'operator: 2 threads bit-identical to 1')
    call t%check(all(z1 == z2), 'circulant preconditioner: 2 threads bit-identical to 1')
    call destroy_fft_operator(op)
    call destroy_circulant_preconditioner(prec)
  end subroutine check_threads

  subroutine check_parity(a, b, mx, my, nu)
    real(real64), intent(in) :: a, b, nu
    integer, intent(in) :: mx, my
    type(status_t) :: st
    type(patch_t) :: patch
    type(fft_operator_t) :: op
    type(circulant_preconditioner_t) :: prec
    real(real64), allocatable :: x(:, :), y(:, :), z(:, :)
    integer, allocatable :: mirror(:)
    integer, allocatable :: cell_of(:, :)
    character(len=64) :: label
    integer :: k, n

    write (label, '(i0, a, i0, a, f3.1)') mx, ' x ', my, ', nu = ', nu
    call ellipse_patch(a, b, mx, my, patch, st)
    n = patch%n
    allocate (cell_of(mx, my), mirror(n))
    cell_of = 0
    do k = 1, n
      cell_of(patch%ix(k), patch%iy(k)) = k
    end do
    do k = 1, n
      mirror(k) = cell_of(patch%ix(k), my + 1 - patch%iy(k))
    end do
    call backward_operators(patch, nu, op, prec)
    ! columns: class +1 field, class -1 field, their sum
    allocate (x(2 * n, 3), y(2 * n, 3), z(2 * n, 3))
    call random_number(x)
    x(1:n, 1) = x(1:n, 1) + x(mirror, 1)                  ! px even
    x(n + 1:, 1) = x(n + 1:, 1) - x(n + mirror, 1)        ! py odd
    x(1:n, 2) = x(1:n, 2) - x(mirror, 2)                  ! px odd
    x(n + 1:, 2) = x(n + 1:, 2) + x(n + mirror, 2)        ! py even
    x(:, 3) = x(:, 1) + x(:, 2)
    call apply_fft_operator(op, x, y)
    call apply_circulant_preconditioner(prec, x, z)
    call check_split(y, mirror, trim(label)//' operator')
    call check_split(z, mirror, trim(label)//' circulant preconditioner')
    call destroy_fft_operator(op)
    call destroy_circulant_preconditioner(prec)

  end subroutine check_parity

  !> nu = 0 on a y-symmetric patch: the dense path's three decoupled systems
  !> (px even; px odd; py even), the iterative path's two parity classes.
  subroutine check_coupled_plan()
    type(status_t) :: st
    type(patch_t) :: patch
    type(subsystem_t), allocatable :: dense(:), iterative(:)
    logical, parameter :: all_cases(n_load_cases) = .true.
    call ellipse_patch(1.3_real64, 0.7_real64, 41, 27, patch, st)
    dense = plan_subsystems(patch, 0.0_real64, .true., all_cases)
    iterative = plan_subsystems(patch, 0.0_real64, .true., all_cases, decouple=.false.)
    call t%check(size(dense) == 3 .and. all(dense%m < patch%n), 'nu = 0, dense path: three decoupled systems')
    call t%check(size(iterative) == 2 .and. iterative(1)%parity_class == 1 .and. &
                 iterative(2)%parity_class == -1 .and. iterative(1)%serves(1) .and. iterative(2)%serves(2) .and. &
                 iterative(2)%serves(3), 'nu = 0, iterative path: the two parity classes (xi; eta and phi)')
    ! the memory check's plan without cell lists has the same systems and sizes
    call same_sizes(patch)
    call ellipse_patch(1.0_real64, 1.0_real64, 24, 24, patch, st)
    call same_sizes(patch)
    call ellipse_patch(1.0_real64, 0.5_real64, 31, 7, patch, st)
    patch%y0 = patch%y0 + patch%dy / 3    ! not mirror-symmetric
    call same_sizes(patch)
  end subroutine check_coupled_plan

  subroutine same_sizes(patch)
    type(patch_t), intent(in) :: patch
    type(subsystem_t), allocatable :: full(:), sizes(:)
    logical, parameter :: some_cases(n_load_cases) = [.true., .false., .true.]
    real(real64) :: nu
    integer :: i, j
    logical :: decouple, same
    character(len=80) :: what
    do i = 0, 1
      nu = 0.3_real64 * i
      do j = 0, 1
        decouple = j == 1
        full = plan_subsystems(patch, nu, .true., some_cases, decouple=decouple)
        sizes = plan_subsystems(patch, nu, .true., some_cases, decouple=decouple, sizes_only=.true.)
        same = size(full) == size(sizes)
        if (same) same = all(full%m == sizes%m) .and. all(full%parity_class == sizes%parity_class)
        write (what, '(a, i0, a, i0, a, f3.1, a, l1)') 'plan sizes_only = full plan (', patch%mx, ' x ', patch%my, &
              ', nu ', nu, ', decouple ', decouple
        call t%check(same, trim(what)//')')
      end do
    end do
  end subroutine same_sizes

  !> r(:, 1), r(:, 2): the results for a field of each class; r(:, 3): for their sum.
  subroutine check_split(r, mirror, what)
    real(real64), intent(in) :: r(:, :)
    integer, intent(in) :: mirror(:)
    character(len=*), intent(in) :: what
    real(real64) :: plus(size(r, 1)), minus(size(r, 1)), worst
    integer :: n
    n = size(mirror)
    plus(1:n) = (r(1:n, 3) + r(mirror, 3)) / 2
    plus(n + 1:) = (r(n + 1:, 3) - r(n + mirror, 3)) / 2
    minus(1:n) = (r(1:n, 3) - r(mirror, 3)) / 2
    minus(n + 1:) = (r(n + 1:, 3) + r(n + mirror, 3)) / 2
    worst = max(maxval(abs(plus - r(:, 1))), maxval(abs(minus - r(:, 2)))) / maxval(abs(r(:, 1:2)))
    print '(a, es9.2)', what//': the projected sum against each class alone ', worst
    call t%check(worst <= 1e-12_real64, what//': each parity class comes back by projection')
  end subroutine check_split

  !> The backward scheme's FFT operator and circulant preconditioner on a
  !> patch, three load cases (G = 1).
  subroutine backward_operators(patch, nu, op, prec)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: nu
    type(fft_operator_t), intent(out) :: op
    type(circulant_preconditioner_t), intent(out) :: prec
    type(scheme_t) :: scheme
    type(operator_table_t) :: table
    scheme%name = 'backward'
    call build_operator_table(patch, scheme, nu, 1.0_real64, table)
    call create_fft_operator(patch, table, 3, op)
    call build_circulant_preconditioner(patch, nu, 3, prec)
  end subroutine backward_operators
end program test_fft_operator
