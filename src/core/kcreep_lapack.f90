!> Explicit interfaces to the LAPACK/BLAS routines kcreep calls, so that the
!> compiler checks every argument.
module kcreep_lapack
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  interface
    subroutine dgetrf(m, n, a, lda, ipiv, info)
      import :: real64
      integer, intent(in) :: m, n, lda
      real(real64), intent(inout) :: a(lda, *)
      integer, intent(out) :: ipiv(*)
      integer, intent(out) :: info
    end subroutine dgetrf
    subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: real64
      character(len=1), intent(in) :: trans
      integer, intent(in) :: n, nrhs, lda, ldb
      real(real64), intent(in) :: a(lda, *)
      integer, intent(in) :: ipiv(*)
      real(real64), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dgetrs
    subroutine dgecon(norm, n, a, lda, anorm, rcond, work, iwork, info)
      import :: real64
      character(len=1), intent(in) :: norm
      integer, intent(in) :: n, lda
      real(real64), intent(in) :: a(lda, *), anorm
      real(real64), intent(out) :: rcond
      real(real64), intent(inout) :: work(*)
      integer, intent(inout) :: iwork(*)
      integer, intent(out) :: info
    end subroutine dgecon
    subroutine dgesvx(fact, trans, n, nrhs, a, lda, af, ldaf, ipiv, equed, r, c, b, ldb, x, ldx, &
                      rcond, ferr, berr, work, iwork, info)
      import :: real64
      character(len=1), intent(in) :: fact, trans
      character(len=1), intent(inout) :: equed
      integer, intent(in) :: n, nrhs, lda, ldaf, ldb, ldx
      real(real64), intent(inout) :: a(lda, *), af(ldaf, *), r(*), c(*), b(ldb, *)
      integer, intent(inout) :: ipiv(*)
      real(real64), intent(out) :: x(ldx, *), rcond, ferr(*), berr(*)
      real(real64), intent(inout) :: work(*)
      integer, intent(inout) :: iwork(*)
      integer, intent(out) :: info
    end subroutine dgesvx
    real(real64) function dlange(norm, m, n, a, lda, work)
      import :: real64
      character(len=1), intent(in) :: norm
      integer, intent(in) :: m, n, lda
      real(real64), intent(in) :: a(lda, *)
      real(real64), intent(inout) :: work(*)
    end function dlange
  end interface
end module kcreep_lapack
