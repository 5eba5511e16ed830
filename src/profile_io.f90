!> profile_io -- tool profile files (docs/PROFILE_FORMAT.md): read a tool
!> (module tools) from a file, write one to a file.
!>
!> FORMAT.  Plain text, coordinates in mm of the tool at rest (the lower
!> tool's rise H is applied by the program).  '#' starts a comment (whole
!> line or trailing); blank lines are skipped; keywords are
!> case-insensitive; fields are separated by blanks, tabs or commas (module
!> text's split_fields).
!>    side upper|lower                   first data line, exactly once
!>    line x1 y1 x2 y2                   segment from (x1,y1) to (x2,y2)
!>    arc  x1 y1 x2 y2 xc yc ccw|cw      arc from (x1,y1) to (x2,y2) about the
!>                                       centre (xc,yc), counter-clockwise or
!>                                       clockwise (sense is required; an arc
!>                                       may exceed 180 degrees)
!> Numbers are read strictly (text's parse_real: digits, sign, point and
!> exponent only, finite; |x| <= 1e6 mm).  Pieces are listed in chain order, left to right
!> overall.  The radius is |start - centre|; |end - centre| must agree
!> within 1e-6 relative.  Each piece must start within 1e-6 mm of the
!> previous piece's end (it is then snapped onto it).  The chain is then
!> validated as tool_init does and checked not to cross itself
!> (find_crossing).  The file is read whole, at most text's
!> max_input_bytes, lines at most max_line_length characters.  Errors are reported as
!> '<path>:<line>: <what>' ('<path>: <what>' for the whole file).
module profile_io
   use kinds, only: dp
   use text, only: next_line, strip_comment, split_fields, parse_real, lower, itoa, num, &
                   max_input_bytes, max_line_length
   use os, only: read_file
   use tools, only: seg_line, segment_type, tool_type, line_segment, arc_segment, tool_init, &
                    check_chain, radius_tol, cross2, in_arc
   implicit none
   private
   public :: read_profile, write_profile

   !> the largest coordinate accepted, mm (a tool a kilometre wide: beyond,
   !> the distances of tool_gap overflow; a fuzzed -1e300 reached a piece
   !> index of -1)
   real(dp), parameter :: max_coordinate = 1.0e6_dp

   !> continuity of consecutive pieces in a file, mm
   real(dp), parameter :: file_cont_tol = 1.0e-6_dp
   !> most fields a data line may have (an arc has 8)
   integer, parameter :: max_fields = 12

contains

   !> READ_PROFILE: read a tool from a profile file (format in the module
   !> header and docs/PROFILE_FORMAT.md).  The tool is at rest.
   !>  path   [in]  file name
   !>  tool   [out] the tool
   !>  errmsg [out] blank on success, else '<path>:<line>: <what is wrong>'
   !>               (or '<path>: ...' for whole-file problems)
   !>  stat   [out] optional: 0 on success, else 1
   subroutine read_profile(path, tool, errmsg, stat)
      character(len=*), intent(in) :: path
      type(tool_type), intent(out) :: tool
      character(len=*), intent(out) :: errmsg
      integer, intent(out), optional :: stat
      character(len=:), allocatable :: contents, why, line
      type(segment_type), allocatable :: segs(:), tmp(:)
      integer, allocatable :: lineof(:), itmp(:)
      integer :: first(max_fields), last(max_fields)
      integer :: ios, pos, lineno, ntok, nseg, side, nneed, k, ibad
      real(dp) :: v(6), gap, cross_at(2)
      character(len=16) :: key
      character(len=400) :: what

      errmsg = ''
      if (present(stat)) stat = 1
      ! read whole, bounded: /dev/zero or a huge file is refused, not read
      ! forever; a directory is named as such
      call read_file(path, max_input_bytes, contents, ios, why)
      if (ios /= 0) then
         errmsg = trim(path)//': cannot read: '//why
         return
      end if
      allocate (segs(16), lineof(16))
      nseg = 0
      side = 0
      lineno = 0
      what = ''
      pos = 1
      do while (pos <= len(contents))
         call next_line(contents, pos, line)
         lineno = lineno + 1
         if (len(line) > max_line_length) then
            what = 'longer than '//itoa(max_line_length)//' characters'
            exit
         end if
         line = strip_comment(line, '#')
         call split_fields(line, first, last, ntok)
         if (ntok == 0) cycle
         key = lower(field(1))
         if (ntok > max_fields) then
            what = 'too many fields'
         else if (side == 0 .and. key /= 'side') then
            what = 'the first data line must be ''side upper'' or ''side lower'''
         else if (key == 'side') then
            if (side /= 0) then
               what = '''side'' given twice'
            else if (ntok /= 2) then
               what = '''side'' needs one word: upper or lower'
            else if (lower(field(2)) == 'upper') then
               side = 1
            else if (lower(field(2)) == 'lower') then
               side = -1
            else
               what = 'side must be upper or lower, not '''//field(2)//''''
            end if
         else if (key == 'line' .or. key == 'arc') then
            nneed = merge(4, 6, key == 'line')
            if (key == 'line' .and. ntok /= 1 + nneed) then
               what = '''line'' needs 4 numbers (x1 y1 x2 y2), found '//itoa(ntok - 1)
            else if (key == 'arc' .and. ntok /= 2 + nneed) then
               what = '''arc'' needs 6 numbers and a sense (x1 y1 x2 y2 xc yc ccw|cw), found '// &
                      itoa(ntok - 1)
            end if
            if (len_trim(what) == 0) then
               do k = 1, nneed
                  if (.not. parse_real(field(1 + k), v(k))) then
                     what = 'not a number: '''//field(1 + k)//''''
                     exit
                  end if
                  if (abs(v(k)) > max_coordinate) then
                     what = 'coordinate '''//field(1 + k)//''' out of range (|x| <= '// &
                            num(max_coordinate)//' mm)'
                     exit
                  end if
               end do
            end if
            if (len_trim(what) == 0 .and. key == 'line') then
               if (norm2(v(3:4) - v(1:2)) <= 0.0_dp) what = 'zero-length line'
            else if (len_trim(what) == 0) then
               if (lower(field(8)) /= 'ccw' .and. lower(field(8)) /= 'cw') then
                  what = 'arc sense must be ccw or cw, not '''//field(8)//''''
               else if (norm2(v(1:2) - v(5:6)) <= 0.0_dp .or. norm2(v(3:4) - v(5:6)) <= 0.0_dp) then
                  what = 'zero arc radius (an end point is the centre)'
               else if (abs(norm2(v(3:4) - v(5:6)) - norm2(v(1:2) - v(5:6))) > &
                        radius_tol*norm2(v(1:2) - v(5:6))) then
                  ! 8 digits (not num's 6): the radii may differ in the 7th
                  write (what, '(a, es14.7, a, es14.7, a)') 'radius mismatch: |start - centre| = ', &
                     norm2(v(1:2) - v(5:6)), ', |end - centre| = ', norm2(v(3:4) - v(5:6)), ' mm'
               else if (norm2(v(3:4) - v(1:2)) <= 0.0_dp) then
                  what = 'zero-length arc (start = end)'
               end if
            end if
            if (len_trim(what) == 0 .and. nseg > 0) then
               gap = norm2(v(1:2) - segs(nseg)%p2)
               if (gap > file_cont_tol) then
                  what = 'piece does not start where the piece on line '//itoa(lineof(nseg))// &
                         ' ends (gap '//num(gap)//' mm)'
               else
                  v(1:2) = segs(nseg)%p2
               end if
            end if
            if (len_trim(what) == 0) then
               if (nseg == size(segs)) then
                  allocate (tmp(2*nseg), itmp(2*nseg))
                  tmp(1:nseg) = segs
                  itmp(1:nseg) = lineof
                  call move_alloc(tmp, segs)
                  call move_alloc(itmp, lineof)
               end if
               nseg = nseg + 1
               lineof(nseg) = lineno
               if (key == 'line') then
                  segs(nseg) = line_segment(v(1:2), v(3:4))
               else
                  segs(nseg) = arc_segment(v(1:2), v(3:4), v(5:6), lower(field(8)) == 'ccw')
               end if
            end if
         else
            what = 'unknown keyword '''//field(1)//''' (expected side, line or arc)'
         end if
         if (len_trim(what) > 0) exit
      end do
      if (len_trim(what) > 0) then
         errmsg = trim(path)//':'//itoa(lineno)//': '//trim(what)
         return
      end if
      if (side == 0) then
         errmsg = trim(path)//': no ''side upper|lower'' line'
         return
      end if
      if (nseg < 1) then
         errmsg = trim(path)//': no pieces (need at least one line or arc)'
         return
      end if
      call check_chain(segs(1:nseg), side, file_cont_tol, .false., what, ibad)
      if (ibad /= 0) then
         ! name the line of the offending piece (the last one for the chain)
         errmsg = trim(path)//':'//itoa(lineof(min(ibad, nseg)))//': '//trim(what)
         return
      end if
      ! (the first of the two pieces may be 0, the continuation before the
      ! chain: the second, k, says whether they meet)
      call find_crossing(segs(1:nseg), ibad, k, cross_at)
      if (k /= 0) then
         errmsg = trim(path)//':'//itoa(lineof(min(k, nseg)))//': '// &
                  piece_name(k)//' crosses '//piece_name(ibad)// &
                  ' at (x, y) = ('//num(cross_at(1))//', '//num(cross_at(2))// &
                  ') mm: the profile must not cross itself'
         return
      end if
      call tool_init(tool, segs(1:nseg), side, what, ibad)
      if (ibad /= 0) then
         errmsg = trim(path)//': '//trim(what)
         return
      end if
      if (present(stat)) stat = 0
   contains
      !> PIECE_NAME: a piece of the chain for a message: 'the piece on line
      !> N', or the chain's straight continuation before its first piece
      !> (k = 0) or after its last (k = nseg + 1).
      !>  k [in]  piece number, 0 to nseg + 1
      function piece_name(k) result(name)
         integer, intent(in) :: k
         character(len=:), allocatable :: name
         if (k == 0) then
            name = 'the continuation before the first piece (line '//itoa(lineof(1))//')'
         else if (k == nseg + 1) then
            name = 'the continuation after the last piece (line '//itoa(lineof(nseg))//')'
         else
            name = 'the piece on line '//itoa(lineof(k))
         end if
      end function piece_name

      !> FIELD: field k (1 <= k <= ntok <= max_fields) of the current line.
      !>  k [in]  field number
      function field(k) result(f)
         integer, intent(in) :: k
         character(len=:), allocatable :: f
         f = line(first(k):last(k))
      end function field
   end subroutine read_profile

   !> FIND_CROSSING: where a chain crosses or touches itself.  Every pair of
   !> pieces is intersected exactly (line-line, line-arc, arc-arc), the
   !> chain's straight continuations beyond its ends (tool_level's tangent
   !> lines, taken far_length long) included as pieces 0 and n + 1;
   !> consecutive pieces share their joint, which does not count (a point
   !> within near_joint times the chain's size of it).  A surface that
   !> crosses itself has no inside: the contact search would then find the
   !> sheet inside one part of the tool and outside another, and blame the
   !> other tool (issue 28, item 7).
   !>  segs      [in]  the chain (validated by check_chain)
   !>  i, j      [out] 0, 0 if the chain does not cross itself; else the
   !>                  two pieces that meet (0 <= i < j <= n + 1)
   !>  at        [out] where they meet, mm
   subroutine find_crossing(segs, i, j, at)
      type(segment_type), intent(in) :: segs(:)
      integer, intent(out) :: i, j
      real(dp), intent(out) :: at(2)
      !> the continuations' length, mm (coordinates are at most 1e6 mm)
      real(dp), parameter :: far_length = 1.0e7_dp
      !> how near the joint of consecutive pieces a meeting point belongs
      !> to the joint, relative to the chain's size (double roots of tangent
      !> pieces are found to about 1e-8 relative)
      real(dp), parameter :: near_joint = 1.0e-6_dp
      type(segment_type) :: pieces(0:size(segs) + 1)
      real(dp) :: pts(2, 2), extent, tol, joint(2)
      integer :: n, np, k
      n = size(segs)
      at = 0.0_dp
      pieces(1:n) = segs
      pieces(0) = line_segment(segs(1)%p1 - far_length*segs(1)%t1, segs(1)%p1)
      pieces(n + 1) = line_segment(segs(n)%p2, segs(n)%p2 + far_length*segs(n)%t2)
      extent = max(maxval(segs%box(2)) - minval(segs%box(1)), maxval(segs%box(4)) - minval(segs%box(3)))
      tol = 1.0e-9_dp*extent
      do i = 0, n + 1
         do j = i + 1, n + 1
            if (any(pieces(i)%box([1, 3]) > pieces(j)%box([2, 4]) + tol) .or. &
                any(pieces(j)%box([1, 3]) > pieces(i)%box([2, 4]) + tol)) cycle
            call meet(pieces(i), pieces(j), tol, pts, np)
            joint = pieces(i)%p2
            do k = 1, np
               if (j == i + 1 .and. norm2(pts(:, k) - joint) <= near_joint*extent) cycle
               at = pts(:, k)
               return
            end do
         end do
      end do
      i = 0
      j = 0
   end subroutine find_crossing

   !> MEET: the points where two pieces meet (at most two are reported;
   !> for overlapping collinear lines or arcs of one circle, the ends of
   !> the overlap).
   !>  a, b  [in]  the pieces
   !>  tol   [in]  distance within which points meet, mm
   !>  pts   [out] pts(:, 1:np) the points
   !>  np    [out] how many (0, 1 or 2)
   subroutine meet(a, b, tol, pts, np)
      type(segment_type), intent(in) :: a, b
      real(dp), intent(in) :: tol
      real(dp), intent(out) :: pts(2, 2)
      integer, intent(out) :: np
      real(dp) :: cand(2, 4), d, along, half_chord, ex(2)
      integer :: nc, k
      np = 0
      pts = 0.0_dp
      nc = 0
      if (a%kind == seg_line .and. b%kind == seg_line) then
         call line_line(a, b)
      else if (a%kind == seg_line) then
         call line_circle(a, b)
      else if (b%kind == seg_line) then
         call line_circle(b, a)
      else
         d = norm2(b%centre - a%centre)
         if (d <= tol .and. abs(a%radius - b%radius) <= tol) then
            ! one circle: the ends of either arc inside the other
            call add(a%p1)
            call add(a%p2)
            call add(b%p1)
            call add(b%p2)
         else if (d > tol .and. d <= a%radius + b%radius + tol .and. &
                  d >= abs(a%radius - b%radius) - tol) then
            ex = (b%centre - a%centre)/d
            along = (a%radius**2 - b%radius**2 + d**2)/(2.0_dp*d)
            half_chord = sqrt(max(a%radius**2 - along**2, 0.0_dp))
            call add(a%centre + along*ex + half_chord*[-ex(2), ex(1)])
            call add(a%centre + along*ex - half_chord*[-ex(2), ex(1)])
         end if
      end if
      ! keep the candidates on both pieces
      do k = 1, nc
         if (np == 2) exit
         if (on_piece(a, cand(:, k)) .and. on_piece(b, cand(:, k))) then
            np = np + 1
            pts(:, np) = cand(:, k)
         end if
      end do
   contains
      !> ADD: one candidate point.
      subroutine add(p)
         real(dp), intent(in) :: p(2)
         nc = nc + 1
         cand(:, nc) = p
      end subroutine add

      !> LINE_LINE: the crossing of two lines, or the ends of their overlap.
      subroutine line_line(l1, l2)
         type(segment_type), intent(in) :: l1, l2
         real(dp) :: r(2), q(2), den, t
         r = l1%p2 - l1%p1
         q = l2%p2 - l2%p1
         den = cross2(r, q)
         if (abs(den) > 1.0e-12_dp*norm2(r)*norm2(q)) then
            t = cross2(l2%p1 - l1%p1, q)/den
            call add(l1%p1 + t*r)
         else if (abs(cross2(r, l2%p1 - l1%p1)) <= tol*norm2(r)) then
            ! collinear: the ends of each inside the other
            call add(l1%p1)
            call add(l1%p2)
            call add(l2%p1)
            call add(l2%p2)
         end if
      end subroutine line_line

      !> LINE_CIRCLE: where a line meets the circle of an arc.
      subroutine line_circle(l, c)
         type(segment_type), intent(in) :: l, c
         real(dp) :: r(2), f(2), qa, qb, qc, disc, t
         integer :: sgn
         r = l%p2 - l%p1
         f = l%p1 - c%centre
         qa = dot_product(r, r)
         qb = 2.0_dp*dot_product(r, f)
         qc = dot_product(f, f) - c%radius**2
         disc = qb**2 - 4.0_dp*qa*qc
         ! a line within tol of tangent touches
         if (disc < -4.0_dp*qa*(2.0_dp*c%radius*tol)) return
         do sgn = -1, 1, 2
            t = (-qb + real(sgn, dp)*sqrt(max(disc, 0.0_dp)))/(2.0_dp*qa)
            call add(l%p1 + t*r)
         end do
      end subroutine line_circle

      !> ON_PIECE: a point (on the piece's line or circle) within the piece.
      pure logical function on_piece(sg, p)
         type(segment_type), intent(in) :: sg
         real(dp), intent(in) :: p(2)
         real(dp) :: r(2), t
         if (norm2(p - sg%p1) <= tol .or. norm2(p - sg%p2) <= tol) then
            on_piece = .true.
         else if (sg%kind == seg_line) then
            r = sg%p2 - sg%p1
            t = dot_product(p - sg%p1, r)/dot_product(r, r)
            on_piece = t >= 0.0_dp .and. t <= 1.0_dp .and. &
                       abs(cross2(r, p - sg%p1)) <= tol*norm2(r)
         else
            on_piece = abs(norm2(p - sg%centre) - sg%radius) <= tol .and. &
                       in_arc(sg, (p - sg%centre)/sg%radius)
         end if
      end function on_piece
   end subroutine meet

   !> WRITE_PROFILE: write a tool as a profile file (the tool at rest),
   !> numbers with 17 significant digits so read_profile gives back the same
   !> pieces.
   !>  path   [in]  file name (replaced if it exists)
   !>  tool   [in]  the tool
   !>  errmsg [out] blank on success, else '<path>: <what>'
   !>  stat   [out] optional: 0 on success, else 1
   !>  header [in]  optional comment lines written after the standard header
   !>               (each prefixed with '# ')
   subroutine write_profile(path, tool, errmsg, stat, header)
      character(len=*), intent(in) :: path
      type(tool_type), intent(in) :: tool
      character(len=*), intent(out) :: errmsg
      integer, intent(out), optional :: stat
      character(len=*), intent(in), optional :: header(:)
      integer :: unit, ios, i
      character(len=256) :: iomsg
      character(len=*), parameter :: fmt_line = '(a, 4(1x, es24.16e3))', &
                                     fmt_arc = '(a, 6(1x, es24.16e3), 1x, a)'
      errmsg = ''
      if (present(stat)) stat = 1
      if (tool%nseg < 1 .or. (tool%side /= 1 .and. tool%side /= -1)) then
         errmsg = trim(path)//': tool is empty or has no side'
         return
      end if
      open (newunit=unit, file=path, status='replace', action='write', iostat=ios, iomsg=iomsg)
      if (ios /= 0) then
         errmsg = trim(path)//': cannot open for writing: '//trim(iomsg)
         return
      end if
      write (unit, '(a)', iostat=ios) '# drawbead tool profile (format: docs/PROFILE_FORMAT.md)'
      write (unit, '(a)', iostat=ios) '# centreline surface in mm at shift 0; pieces left to right'
      if (present(header)) then
         do i = 1, size(header)
            write (unit, '(a)', iostat=ios) '# '//trim(header(i))
         end do
      end if
      write (unit, '(a)', iostat=ios) 'side '//merge('upper', 'lower', tool%side == 1)
      do i = 1, tool%nseg
         if (ios /= 0) exit
         associate (s => tool%seg(i))
            if (s%kind == seg_line) then
               write (unit, fmt_line, iostat=ios, iomsg=iomsg) 'line', s%p1, s%p2
            else
               write (unit, fmt_arc, iostat=ios, iomsg=iomsg) 'arc ', s%p1, s%p2, s%centre, &
                  trim(merge('ccw', 'cw ', s%sense == 1))
            end if
         end associate
      end do
      close (unit)
      if (ios /= 0) then
         errmsg = trim(path)//': write error: '//trim(iomsg)
         return
      end if
      if (present(stat)) stat = 0
   end subroutine write_profile

end module profile_io
