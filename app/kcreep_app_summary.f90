!> The summary a single case prints: patch, scheme, coefficients against
!> Kalker's table, the CONTACT comparison, extrapolation, solver diagnostics,
!> times, verdict and warnings.
module kcreep_app_summary
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, real64
  use kcreep, only: kcreep_version, patch_t, normalised_about
  use kcreep_namelist, only: config_t
  use kcreep_table, only: run_record_t
  use kcreep_contact_compare, only: comparison_lines, contact_spin_shift
  implicit none
  private
  public :: print_summary

contains

  !> The summary of a single case on standard output; warnings also on standard error.
  subroutine print_summary(input_path, cfg, record)
    character(len=*), intent(in) :: input_path
    type(config_t), intent(in) :: cfg
    type(run_record_t), intent(in) :: record
    character(len=*), parameter :: fmt_c = '(2x, a, es12.5, a, f8.4, a, f8.3, a)'
    type(patch_t) :: patch
    character(len=3), parameter :: names(3) = ['C11', 'C22', 'C23']
    character(len=64) :: label, note
    integer :: i
    real(real64) :: about_centroid(3)

    patch = record%patch
    write (output_unit, '(a)') 'kcreep '//kcreep_version//': '//input_path
    if (record%method == 'table') then
      write (output_unit, '(2x, a, g0.6, a, es10.3, a, i0, a, i0, a)') 'patch: ellipse, a/b = ', &
        patch%semi_a / patch%semi_b, ', c = ', record%c, ' (its ', patch%mx, ' x ', patch%my, &
        ' grid only for FASTSIM: nothing is solved)'
    else
      write (output_unit, '(2x, a, i0, a, i0, a, i0, a, es10.3)') 'patch: '//patch%kind//', grid ', &
        patch%mx, ' x ', patch%my, ', ', patch%n, ' cells, c = ', record%c
    end if
    write (output_unit, '(2x, a, 2es14.6, a, 2es14.6, a)') 'centroid (xc, yc):', record%centroid, &
      ';  spin centre:', record%spin_centre, ' ('//cfg%spin_centre//')'
    if (record%method == 'table') then
      write (output_unit, '(2x, a, g0.4, a, es10.3)') 'scheme: none (method = '''//cfg%solve%method// &
        '''), nu = ', cfg%nu, ', G = ', cfg%g
    else if (cfg%scheme%name == 'collocation') then
      write (output_unit, '(2x, a, f6.3, a, g0.4, a, es10.3)') 'scheme: collocation, alpha = ', &
        cfg%scheme%alpha, ', nu = ', cfg%nu, ', G = ', cfg%g
    else
      write (output_unit, '(2x, a, g0.4, a, es10.3)') 'scheme: backward, nu = ', cfg%nu, ', G = ', cfg%g
    end if
    write (output_unit, '(2x, a, 3es14.6)') 'f11 f22 f23:', record%f(1, 1), record%f(2, 2), record%f(2, 3)
    do i = 1, 3
      if (record%klt(i) == record%klt(i)) then
        write (output_unit, fmt_c) names(i)//' = ', record%cn(i), '   Kalker ', record%klt(i), &
          '   (', 100 * (record%cn(i) / record%klt(i) - 1), ' %)'
      else
        write (output_unit, '(2x, a, es12.5)') names(i)//' = ', record%cn(i)
      end if
    end do
    if (patch%kind == 'contact') call print_contact_comparison(cfg, record)
    if (record%normal_solved) call print_normal(record)
    if (record%extrapolated) then
      write (output_unit, '(2x, a, i0, a, i0, a)') 'extrapolated (', cfg%extrapolate_levels, &
        ' levels, ratio ', cfg%refine_ratio, '; the rows above are the finest level):'
      do i = 1, 3
        write (output_unit, '(4x, a, f9.5, a, es8.1, a, f5.2, a)') names(i)//' -> ', record%ext(i), &
          ' +- ', record%ext_error(i), '   (order ', record%ext_order(i), ')'
      end do
    end if
    if (any(record%err == record%err)) then
      ! a coefficient without an estimate (its load case not run) shows '-'
      label = 'estimated relative error of C11 C22 C23:'
      if (record%method == 'table') label = 'stated relative uncertainty of C11 C22 C23:'
      note = ''
      if (cfg%target_error > 0) note = '   (target '//trim(rtoa_short(cfg%target_error))//', C23 3 times it)'
      write (output_unit, '(2x, a)', advance='no') trim(label)
      do i = 1, 3
        if (record%err(i) == record%err(i)) then
          write (output_unit, '(es9.1)', advance='no') record%err(i)
        else
          write (output_unit, '(a9)', advance='no') '-'
        end if
      end do
      write (output_unit, '(a)') trim(note)
    else
      write (output_unit, '(2x, a)') 'estimated relative error of C11 C22 C23: none (see the warnings)'
    end if
    write (output_unit, '(2x, a, 3es12.4, a)') 'FASTSIM L1 L2 L3:', record%fastsim, '  (length^3/force)'
    if (patch%kind /= 'ellipse') then
      ! the patch's C23 about its centroid, as Kalker's about the ellipse's centre
      ! (moving the centre mixes f's columns: without the phi case C11 and C22,
      ! which do not depend on it, as they are)
      about_centroid = record%cn
      if (all(record%f == record%f)) &
        about_centroid = normalised_about(record%f, record%g, record%c, record%centroid - record%spin_centre)
      do i = 1, 2
        associate (e => record%ellipse(i))
          write (output_unit, '(2x, a)') 'equivalent ellipse ('//trim(e%kind)//'): a/b = '// &
            columns([e%semi_a / e%semi_b], 4, 0)//', Kalker C11 C22 C23 ='//columns(e%c, 4, 8)// &
            ' ('//columns(100 * (e%c / about_centroid - 1), 2, 7)//' %)'
          write (output_unit, '(4x, a, 3es12.4, a)') 'its L1 L2 L3:', e%flex, ' ('// &
            columns(100 * (e%flex / record%fastsim - 1), 2, 7)//' % against the exact L)'
        end associate
      end do
    end if
    if (record%method == 'table' .and. cfg%solve%method == 'auto') then
      write (output_unit, '(2x, a)') 'method: table, chosen by method = ''auto'' (the refined table''s stated '// &
        'uncertainty meets the target; nothing solved, no tractions; method = ''iterative'' solves, docs/accuracy.md)'
    else if (record%method == 'table') then
      write (output_unit, '(2x, a)') 'method: table (interpolated in kcreep''s refined table of Kalker''s '// &
        'coefficients, docs/accuracy.md; nothing solved, no tractions)'
    else if (record%method == 'dense') then
      write (output_unit, '(2x, a)') 'method: dense LU (LAPACK)'
      write (output_unit, '(2x, a, es9.2, a, es9.2)') 'rcond ', record%rcond, ', backward error ', record%backward_error
      write (output_unit, '(2x, a, es9.2, a, es9.2, a)') 'solve: relative residual ', record%relative_residual, &
        ', backward error before refinement ', record%backward_error_initial, ', refine = '//trim(record%refine)
    else
      write (output_unit, '(2x, a, i0, a, es9.2, a)') 'method: iterative (FFT operator, preconditioned GMRES), ', &
        record%iterations, ' iterations, relative residual ', record%backward_error, ' (no rcond estimate)'
    end if
    if (record%method /= 'table') then
      if (cfg%solve%threads > 0) then
        write (output_unit, '(2x, a, i0, a)') 'threads: ', record%threads, ' (&solver threads)'
      else
        write (output_unit, '(2x, a, i0, a)') 'threads: ', record%threads, &
          ' (automatic: CPUs this process may use that were free, where the work pays; docs/performance.md)'
      end if
    end if
    write (output_unit, '(2x, a, 4f9.3)') 'time assemble factor solve total [s]:', record%t_assemble, &
      record%t_factor, record%t_solve, record%t_total
    write (output_unit, '(2x, a)') 'verdict: '//record%verdict//'   table: '//cfg%table_file
    do i = 1, size(record%warnings)
      write (output_unit, '(2x, a)') 'WARNING: '//trim(record%warnings(i))
      write (error_unit, '(a)') 'kcreep: warning: '//trim(record%warnings(i))
    end do
  end subroutine print_summary

  !> shape = 'gap': the normal problem behind the patch.
  subroutine print_normal(record)
    type(run_record_t), intent(in) :: record
    real(real64) :: centroid(2)
    centroid = record%patch%centroid()
    write (output_unit, '(2x, a, es12.5, a, es12.5, a, es12.5)') 'normal: fn = ', record%fn, ', approach = ', &
      record%approach, ', pmax = ', record%pmax
    write (output_unit, '(2x, a, i0, a, es12.5, a, 2es12.4)') 'contact area: ', record%patch%n, ' cells, area ', &
      record%patch%area(), ', centroid ', centroid
    write (output_unit, '(2x, a, 4es12.4)') 'contact bounding box x, y: ', record%bbox
    write (output_unit, '(2x, a, i0, a, es9.2)') 'normal solve: ', record%normal_iterations, &
      ' iterations (constrained CG), complementarity residual ', record%normal_residual
  end subroutine print_normal

  !> shape = 'contact': kcreep's forces for CONTACT's creepages beside CONTACT's.
  subroutine print_contact_comparison(cfg, record)
    type(config_t), intent(in) :: cfg
    type(run_record_t), intent(in) :: record
    character(len=300), allocatable :: lines(:)
    integer :: i
    lines = comparison_lines(cfg%contact, record%f, cfg%scheme%name == 'backward' .and. &
                             cfg%scheme%spin_shift == contact_spin_shift)
    do i = 1, size(lines)
      write (output_unit, '(2x, a)') trim(lines(i))
    end do
  end subroutine print_contact_comparison

  !> values in fixed point with the given decimals, each right-aligned in at
  !> least width characters and after one blank, so that columns never run
  !> together (scientific notation where fixed point would not fit in 12).
  pure function columns(values, decimals, width) result(text)
    real(real64), intent(in) :: values(:)
    integer, intent(in) :: decimals, width
    character(len=:), allocatable :: text
    character(len=32) :: buf
    character(len=16) :: fmt
    integer :: i
    text = ''
    write (fmt, '(a, i0, a)') '(f12.', decimals, ')'
    do i = 1, size(values)
      write (buf, fmt) values(i)
      if (index(buf, '*') > 0 .or. values(i) /= values(i)) write (buf, '(es12.4)') values(i)
      buf = adjustl(buf)
      text = text//repeat(" ", max(1, width - len_trim(buf)))//trim(buf)
    end do
    if (width == 0) text = adjustl(text)
    text = trim(text)
  end function columns

  function rtoa_short(x) result(text)
    real(kind(1.0d0)), intent(in) :: x
    character(len=16) :: text
    write (text, '(es8.1)') x
    text = adjustl(text)
  end function rtoa_short

end module kcreep_app_summary
