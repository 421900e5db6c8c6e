; Reference laser gate, PIC16F628A (docs/gate-firmware.md, "The PIC gate"), gpasm.
; 4 MHz crystal (XT), instruction cycle 1 us. USART 9600 8N1 (BRGH 1, SPBRG 25: 9615 baud), polled.
; Pulse train: CCP1 PWM on RB3 from Timer2 (hardware), 2 us pulses. Below 977 Hz the period is k Timer2 periods of
; 127..256 x 4 us (the Timer2 interrupt sets PR2 and lets CCP1's double-buffered duty through on every k-th only).
; BURST counts in hardware: a jumper from RB3/CCP1 to RA4/T0CKI clocks Timer0, preloaded so that it overflows on the
; n-th pulse (counting its overflows above 256); the overflow interrupt's first instructions stop Timer2 a few us
; after the n-th pulse began, before the next (10 us later at 100 kHz). Timer1 gives the 1.024 ms tick.
; Implements: *IDN?, PING, OFF, FREQ <hz> (0..100000), BURST <n> <hz> (n 1..1000000, hz 1..100000), STATE?,
; WDOG <ms> (0 or 50..60000) and the watchdog (Timer1, 1.024 ms tick) with TRIPPED in STATE?. Not: keywords in lower
; case, tabs, several spaces, signs (ERR 1 / ERR 3), lines over 24 bytes (ERR 1 UNKNOWN, as the full protocol does
; over 128), numbers of 8 digits or more (ERR 2 RANGE where the twin says ERR 3 SYNTAX beyond the 32-bit range).
        processor p16f628a
        radix dec
        #include <p16f628a.inc>
        __config _XT_OSC & _WDT_OFF & _PWRTE_ON & _MCLRE_ON & _BOREN_ON & _LVP_OFF & _CP_OFF
        errorlevel -302

LINEMAX equ 24
        cblock 0x20
          line:LINEMAX
          len, over
          num0, num1, num2
          dig:8
          ndig
          fdig:8
          wdig:6
          wd0, wd1
          ms0, ms1
          flags
          tmp, cnt, ptr, src
          q0, q1, q2, r0, r1, r2, d0, d1, d2
          t0, t1, t2
          txc
          pend                  ; where parse stopped
          bn0, bn1, bn2         ; BURST's count
          ram0_end
        endc
        if ram0_end > 0x70
          error "bank 0 variables run into the shared RAM"
        endif
        ; shared by all banks (0x70..0x7F): what the interrupt touches before it knows the bank
        cblock 0x70
          armed                 ; bit 0: the next Timer1 overflow ends the burst and the train is fast (stop at once)
                                ; bit 1: the next Timer1 overflow ends the burst
          w_save, s_save
          ovf0, ovf1            ; Timer0 overflows still to come in the burst, the last included
          bflags                ; DONE: the burst counted itself out (the main loop folds it in); SLOW; BURSTING
          sl0, sl1              ; Timer2 periods left in this pulse period (SLOW)
          rl0, rl1              ; long ones left
          w_tmp
          kk0, kk1              ; below 977 Hz: Timer2 periods a pulse period (k), of which rr long ones
          rr0, rr1
          bm1                   ; the short ones' PR2
          shared_end
        endc
        if shared_end > 0x80
          error "shared variables beyond 0x7F"
        endif
DONE    equ 0
SLOW    equ 1
BURSTING equ 2
FIRING  equ 0
TRIPPED equ 1

        org 0
        goto start

; ---- interrupt: Timer1 (the burst's counter) and, below 977 Hz, Timer2 ----
        org 4
        btfsc armed, 0          ; the last pulse of a fast burst has begun (and ended: it lasts 2 us, less than the
        bcf T2CON, TMR2ON       ; interrupt's latency): Timer2 stopped, no period begins again, RB3 stays low; neither
        goto isr                ; touches STATUS or W, and main code never leaves bank 0 with T0IE set

; ---- message table (retlw), each message ends with 0 ----
        org 0x10
msg:    movwf PCL               ; PCLATH = 0, table inside the first 256 words
m_idn   equ $
        dt "OK PICGATE PIC-1.0", 0
m_pong  equ $
        dt "OK PONG", 0
m_off   equ $
        dt "OK FREQ 0", 0
m_freq  equ $
        dt "OK FREQ ", 0
m_wdog  equ $
        dt "OK WDOG ", 0
m_state equ $
        dt "OK STATE ", 0
m_on    equ $
        dt " ON WDOG ", 0
m_noton equ $
        dt " OFF WDOG ", 0
m_trip  equ $
        dt " TRIPPED", 0
m_e1    equ $
        dt "ERR 1 UNKNOWN", 0
m_e2    equ $
        dt "ERR 2 RANGE", 0
m_e3    equ $
        dt "ERR 3 SYNTAX", 0
m_burst equ $
        dt "OK BURST ", 0

start:
        clrf PORTB
        movlw 0x07
        movwf CMCON             ; comparators off
        bsf STATUS, RP0
        movlw b'11110111'       ; RB3 (CCP1) output, RB1 RX / RB2 TX as the USART wants (RA4/T0CKI an input)
        movwf TRISB
        movlw 25
        movwf SPBRG
        movlw b'00100100'       ; TXEN, BRGH
        movwf TXSTA
        movlw b'11101000'       ; Timer0 counts RA4/T0CKI's rising edges, no prescaler (pull-ups off)
        movwf OPTION_REG
        bcf STATUS, RP0
        movlw b'10010000'       ; SPEN, CREN
        movwf RCSTA
        clrf CCP1CON
        clrf T2CON
        movlw 0xFC              ; the first tick 1024 us from now, as every other
        movwf TMR1H
        movlw b'00000001'       ; Timer1: instruction clock, 1:1, on (the tick)
        movwf T1CON
        clrf armed
        clrf bflags
        bsf INTCON, GIE
        clrf len
        clrf over
        clrf flags
        clrf ms0
        clrf ms1
        movlw low 977           ; watchdog 1000 ms at power-up: 977 ticks of 1.024 ms
        movwf wd0
        movlw high 977
        movwf wd1
        movlw '1'
        movwf wdig
        movlw '0'
        movwf wdig+1
        movwf wdig+2
        movwf wdig+3
        clrf wdig+4
        movlw '0'
        movwf fdig
        clrf fdig+1
        bcf PIR1, TMR1IF

loop:   btfsc bflags, DONE
        call fold
        btfsc PIR1, TMR1IF
        call tick
        btfsc RCSTA, OERR       ; overrun: restart the receiver
        call rx_restart
        btfss PIR1, RCIF
        goto loop
        movf RCREG, W
        movwf tmp
        xorlw 0x0A
        btfsc STATUS, Z
        goto got_line
        movlw LINEMAX
        subwf len, W            ; C set when len >= LINEMAX
        btfsc STATUS, C
        goto too_long
        movlw line
        addwf len, W
        movwf FSR
        movf tmp, W
        movwf INDF
        incf len, F
        goto loop
too_long:
        bsf over, 0
        goto loop
got_line:
        call do_line
        clrf len
        clrf over
        goto loop

rx_restart:
        bcf RCSTA, CREN
        bsf RCSTA, CREN
        return

; ---- 1.024 ms tick: counts the silence; switches off when it passes the watchdog time while firing ----
; Timer1 overflowed a while ago: TMR1H + 0xFC (- 4) makes the next overflow 1024 us after this one (TMR1L runs on);
; a carry says a whole tick more has gone by (a line was being processed): the next poll counts it at once.
tick:   bcf PIR1, TMR1IF
        movlw 0xFC
        addwf TMR1H, F
        btfsc STATUS, C
        bsf PIR1, TMR1IF
        incfsz ms0, F
        goto tick_chk
        incfsz ms1, F
        goto tick_chk
        decf ms1, F             ; saturate at 0xFFFF
        decf ms0, F
tick_chk:
        btfss flags, FIRING
        return
        btfsc bflags, DONE      ; a burst that ended by itself is off already (folded in by the main loop, not here:
        return                  ; the tick also runs while a reply is sent, STATE?'s frequency digits among them)
        movf wd0, W
        iorwf wd1, W
        btfsc STATUS, Z
        return                  ; watchdog off
        movf ms1, W             ; ms > wd ? (so never before the watchdog time, at most a tick after it)
        subwf wd1, W            ; wd1 - ms1: a borrow means ms1 > wd1
        btfss STATUS, C
        goto trip
        btfss STATUS, Z
        return
        movf ms0, W
        subwf wd0, W
        btfsc STATUS, C
        return
trip:   call pwm_off
        bsf flags, TRIPPED
        return

; ---- a line has arrived ----
do_line:
        clrf ms0                ; any line feeds the watchdog
        clrf ms1
        btfsc bflags, DONE
        call fold
        btfsc over, 0
        goto err1
        movf len, W             ; drop a trailing '\r'
        btfsc STATUS, Z
        return
        addlw line - 1
        movwf FSR
        movf INDF, W
        xorlw 0x0D
        btfsc STATUS, Z
        decf len, F
        movf len, W
        btfsc STATUS, Z
        return                  ; empty line: heard, not answered
        ; *IDN?
        movlw 5
        xorwf len, W
        btfss STATUS, Z
        goto not_idn
        movf line, W
        xorlw '*'
        btfss STATUS, Z
        goto not_idn
        movf line+1, W
        xorlw 'I'
        btfss STATUS, Z
        goto not_idn
        movf line+4, W
        xorlw '?'
        btfss STATUS, Z
        goto not_idn
        movlw m_idn
        goto reply
not_idn:
        ; PING
        movlw 4
        xorwf len, W
        btfss STATUS, Z
        goto not_ping
        movf line, W
        xorlw 'P'
        btfss STATUS, Z
        goto not_ping
        movf line+1, W
        xorlw 'I'
        btfss STATUS, Z
        goto not_ping
        movf line+3, W
        xorlw 'G'
        btfss STATUS, Z
        goto not_ping
        movlw m_pong
        goto reply
not_ping:
        ; OFF
        movlw 3
        xorwf len, W
        btfss STATUS, Z
        goto not_off
        movf line, W
        xorlw 'O'
        btfss STATUS, Z
        goto not_off
        movf line+2, W
        xorlw 'F'
        btfss STATUS, Z
        goto not_off
        call pwm_off
        movlw m_off
        goto reply
not_off:
        ; STATE?
        movlw 6
        xorwf len, W
        btfss STATUS, Z
        goto not_state
        movf line, W
        xorlw 'S'
        btfss STATUS, Z
        goto not_state
        movf line+5, W
        xorlw '?'
        btfss STATUS, Z
        goto not_state
        goto state
not_state:
        ; FREQ and WDOG: keyword, one space, digits
        movf line, W
        xorlw 'F'
        btfss STATUS, Z
        goto not_freq
        movf line+1, W
        xorlw 'R'
        btfss STATUS, Z
        goto not_freq
        movf line+3, W
        xorlw 'Q'
        btfss STATUS, Z
        goto not_freq
        movlw 4
        xorwf len, W
        btfsc STATUS, Z
        goto err3               ; FREQ alone
        movf line+4, W
        xorlw ' '
        btfss STATUS, Z
        goto err1
        movlw line + 5
        call parse
        xorlw 0
        btfss STATUS, Z
        goto err_w
        call at_end
        btfss STATUS, Z
        goto err3               ; more than one argument
        goto freq
not_freq:
        ; BURST n hz
        movf line, W
        xorlw 'B'
        btfss STATUS, Z
        goto not_burst
        movf line+1, W
        xorlw 'U'
        btfss STATUS, Z
        goto not_burst
        movf line+4, W
        xorlw 'T'
        btfss STATUS, Z
        goto not_burst
        movlw 5
        xorwf len, W
        btfsc STATUS, Z
        goto err3               ; BURST alone
        movf line+5, W
        xorlw ' '
        btfss STATUS, Z
        goto err1
        goto burst
not_burst:
        movf line, W
        xorlw 'W'
        btfss STATUS, Z
        goto err1
        movf line+1, W
        xorlw 'D'
        btfss STATUS, Z
        goto err1
        movf line+3, W
        xorlw 'G'
        btfss STATUS, Z
        goto err1
        movlw 4
        xorwf len, W
        btfsc STATUS, Z
        goto err3
        movf line+4, W
        xorlw ' '
        btfss STATUS, Z
        goto err1
        movlw line + 5
        call parse
        xorlw 0
        btfss STATUS, Z
        goto err_w
        call at_end
        btfss STATUS, Z
        goto err3
        goto wdog

wd_sub: movf num0, W             ; t -= num1:num0 (t2 borrows)
        subwf t0, F
        movf num1, W
        btfss STATUS, C
        incfsz num1, W
        subwf t1, F
        btfss STATUS, C
        decf t2, F
        return

at_end: movlw line              ; Z set when parse stopped at the line's end
        addwf len, W
        xorwf pend, W
        return

err_w:  xorlw 3                 ; parse returned 2 or 3
        btfsc STATUS, Z
        goto err3
        goto err2
err1:   movlw m_e1
        goto reply
err2:   movlw m_e2
        goto reply
err3:   movlw m_e3
        goto reply

; ---- FREQ n ----
freq:   movf num0, W
        iorwf num1, W
        iorwf num2, W
        btfsc STATUS, Z
        goto freq_zero
        call hz_max
        btfss STATUS, Z
        goto err2
        bcf bflags, BURSTING
        call pwm_on
        call keep_digits
        movlw m_freq
        call send
        movlw dig
        goto send_ram_line
freq_zero:
        call pwm_off
        movlw m_off
        goto reply

; Z set when num <= 100000 (0x0186A0)
hz_max: movf num2, W
        btfsc STATUS, Z
        goto z_set
        xorlw 0x01
        btfss STATUS, Z
        return                  ; num2 > 1
        movlw 0x86
        subwf num1, W
        btfss STATUS, C
        goto z_set              ; num1 < 0x86
        btfss STATUS, Z
        goto z_clr              ; num1 > 0x86
        movlw 0xA1
        subwf num0, W
        btfsc STATUS, C
        goto z_clr              ; num0 >= 0xA1
z_set:  bsf STATUS, Z
        return
z_clr:  bcf STATUS, Z
        return

; ---- BURST n hz: both numbers, both ranges, then the train (the old one stopped first), then the reply ----
burst:  movlw line + 6
        call parse
        xorlw 0
        btfss STATUS, Z
        goto err_w
        call at_end
        btfsc STATUS, Z
        goto err3               ; one argument
        movf pend, W
        movwf FSR
        movf INDF, W
        xorlw ' '
        btfss STATUS, Z
        goto err3
        movf num0, W
        movwf bn0
        movf num1, W
        movwf bn1
        movf num2, W
        movwf bn2
        incf pend, W
        call parse
        xorlw 0
        btfss STATUS, Z
        goto err_w
        call at_end
        btfss STATUS, Z
        goto err3               ; three arguments
        movf num0, W            ; hz 1..100000
        iorwf num1, W
        iorwf num2, W
        btfsc STATUS, Z
        goto err2
        call hz_max
        btfss STATUS, Z
        goto err2
        movf bn0, W             ; n 1..1000000 (0x0F4240)
        iorwf bn1, W
        iorwf bn2, W
        btfsc STATUS, Z
        goto err2
        movlw 0x0F
        subwf bn2, W
        btfss STATUS, C
        goto b_ok
        btfss STATUS, Z
        goto err2
        movlw 0x42
        subwf bn1, W
        btfss STATUS, C
        goto b_ok
        btfss STATUS, Z
        goto err2
        movlw 0x41
        subwf bn0, W
        btfsc STATUS, C
        goto err2
b_ok:   bsf bflags, BURSTING
        call pwm_on
        call keep_digits
        movlw line + 6          ; n's digits again, for the reply
        call parse
        movlw m_burst
        call send
        movlw dig
        goto send_ram_line

; ---- a burst that counted itself out (the interrupt stopped it): off, as STATE? says ----
fold:   bcf bflags, DONE
        bcf bflags, BURSTING
        bcf flags, FIRING
        movlw '0'
        movwf fdig
        clrf fdig+1
        return

keep_digits:                    ; fdig = dig
        movlw 8
        movwf cnt
        movlw dig
        movwf src
        movlw fdig
        movwf ptr
kd:     movf src, W
        movwf FSR
        movf INDF, W
        movwf tmp
        movf ptr, W
        movwf FSR
        movf tmp, W
        movwf INDF
        incf src, F
        incf ptr, F
        decfsz cnt, F
        goto kd
        return

; ---- WDOG n ----
wdog:   movf num2, W
        btfss STATUS, Z
        goto err2
        movf num0, W
        iorwf num1, W
        btfsc STATUS, Z
        goto wdog_ok
        movf num1, W            ; >= 50
        btfss STATUS, Z
        goto wdog_max
        movlw 50
        subwf num0, W
        btfss STATUS, C
        goto err2
wdog_max:                       ; <= 60000 (0xEA60)
        movlw 0xEA
        subwf num1, W
        btfss STATUS, C
        goto wdog_ok
        btfss STATUS, Z
        goto err2
        movlw 0x61
        subwf num0, W
        btfsc STATUS, C
        goto err2
wdog_ok:
        ; ticks = ceil(ms x 125 / 128): never before the time asked (ms x 125 = ms x 128 - ms x 2 - ms, 24 bits)
        clrf t2
        movf num1, W
        movwf t1
        movf num0, W
        movwf t0
        movlw 7
        movwf cnt
wd_shl: bcf STATUS, C
        rlf t0, F
        rlf t1, F
        rlf t2, F
        decfsz cnt, F
        goto wd_shl
        call wd_sub             ; - ms, three times
        call wd_sub
        call wd_sub
        movlw 127               ; + 127, then >> 7
        addwf t0, F
        btfss STATUS, C
        goto wd_r
        incf t1, F
        btfsc STATUS, Z
        incf t2, F
wd_r:   rlf t0, W               ; bit 7 into C
        rlf t1, W
        movwf wd0
        rlf t2, W
        movwf wd1
        movlw 6
        movwf cnt
        movlw dig
        movwf src
        movlw wdig
        movwf ptr
        call kd
        movlw m_wdog
        call send
        movlw dig
        goto send_ram_line

; ---- STATE? ----
state:  movlw m_state
        call send
        movlw fdig
        call send_ram
        movlw m_on
        btfss flags, FIRING
        movlw m_noton
        call send
        movlw wdig
        call send_ram
        btfss flags, TRIPPED
        goto state_end
        movlw m_trip
        call send
        bcf flags, TRIPPED
state_end:
        goto line_end

; ---- parse: digits from W (a line address) to the line's end -> num (24 bits) and dig (no leading zeros) ----
; returns W = 0 ok, 3 not a number, 2 more than six significant digits
parse:  movwf FSR
        movwf t2                ; the start: no digit at all is not a number
        clrf num0
        clrf num1
        clrf num2
        clrf ndig
        movlw line
        addwf len, W
        movwf tmp               ; end address
        movf FSR, W
        xorwf tmp, W
        btfsc STATUS, Z
        retlw 3                 ; nothing after the space
p_next: movf FSR, W
        xorwf tmp, W
        btfsc STATUS, Z
        goto p_done
        movf INDF, W
        xorlw ' '
        btfsc STATUS, Z
        goto p_done             ; the next argument's space
        movf INDF, W
        addlw 0xD0              ; - '0'
        movwf t0                ; digit value if a digit
        movlw 10
        subwf t0, W
        btfsc STATUS, C
        retlw 3                 ; not 0..9
        incf FSR, F
        movf t0, W
        iorwf ndig, W           ; leading zero: skip
        btfsc STATUS, Z
        goto p_next
        movlw 7
        subwf ndig, W
        btfsc STATUS, C
        retlw 2                 ; eighth significant digit
        movf FSR, W             ; keep FSR while storing the digit
        movwf src
        movlw dig
        addwf ndig, W
        movwf FSR
        movf t0, W
        addlw '0'
        movwf INDF
        incf ndig, F
        movf src, W
        movwf FSR
        ; num = num * 10 + digit
        bcf STATUS, C
        rlf num0, F
        rlf num1, F
        rlf num2, F             ; x2
        movf num0, W
        movwf t1
        movf num1, W
        movwf r1
        movf num2, W
        movwf r2                ; r = x2
        bcf STATUS, C
        rlf num0, F
        rlf num1, F
        rlf num2, F
        bcf STATUS, C
        rlf num0, F
        rlf num1, F
        rlf num2, F             ; x8
        movf t1, W
        addwf num0, F
        movf r1, W
        btfsc STATUS, C
        incfsz r1, W
        addwf num1, F
        movf r2, W
        btfsc STATUS, C
        incfsz r2, W
        addwf num2, F           ; x10
        movf t0, W
        addwf num0, F
        btfss STATUS, C
        goto p_next
        incfsz num1, F
        goto p_next
        incf num2, F
        goto p_next
p_done: movf FSR, W
        movwf pend
        xorwf t2, W
        btfsc STATUS, Z
        retlw 3
        movf ndig, W            ; all zeros: "0"
        btfss STATUS, Z
        goto p_term
        movlw '0'
        movwf dig
        incf ndig, F
p_term: movlw dig
        addwf ndig, W
        movwf FSR
        clrf INDF
        retlw 0

; ---- the PWM ----
pwm_off:
        bcf INTCON, T0IE        ; no burst interrupt from here on
        bcf INTCON, PEIE
        clrf CCP1CON            ; RB3 back to its latch, low
        clrf T2CON
        clrf armed
        movlw b'11111000'       ; not DONE, SLOW nor BURSTING... BURSTING is set again by BURST before pwm_on
        andwf bflags, F
        bcf flags, FIRING
        movlw '0'               ; STATE? says 0 Hz
        movwf fdig
        clrf fdig+1
        return

; Starts the train at num Hz (1..100000): a burst of bn pulses when BURSTING. The first pulse begins one Timer2 tick
; after T2CON is written. period P = (1000000 + n/2) / n us: up to 256 us Timer2 at 1:1, PR2 = P - 1; else
; U = (250000 + n/2) / n units of 4 us: up to 256 Timer2 at 1:4, PR2 = U - 1; else (below 977 Hz) SLOW.
pwm_on: btfss bflags, BURSTING
        goto pwm_on2
        call pwm_off
        bsf bflags, BURSTING
        goto pwm_on3
pwm_on2:
        call pwm_off
pwm_on3:
        movlw 0x40              ; 1000000 = 0x0F4240
        movwf q0
        movlw 0x42
        movwf q1
        movlw 0x0F
        movwf q2
        call div_hz             ; q = period in us
        movf q2, W
        iorwf q1, W
        btfsc STATUS, Z
        goto pre1               ; < 256
        movf q2, W
        btfss STATUS, Z
        goto not1
        decf q1, W
        iorwf q0, W
        btfsc STATUS, Z
        goto pre1               ; exactly 256
not1:   movlw 0x90              ; 250000 = 0x03D090
        movwf q0
        movlw 0xD0
        movwf q1
        movlw 0x03
        movwf q2
        call div_hz             ; q = U, the period in 4 us units
        movf q2, W
        iorwf q1, W
        btfsc STATUS, Z
        goto pre4
        movf q2, W
        btfss STATUS, Z
        goto slow
        decf q1, W
        iorwf q0, W
        btfsc STATUS, Z
        goto pre4               ; exactly 256
slow:   ; k = (U + 255) >> 8 Timer2 periods; b = U / k units each, the first r = U - k b of them one longer
        movlw 255
        addwf q0, W
        movlw 0
        btfsc STATUS, C
        movlw 1
        addwf q1, W
        movwf kk0
        movlw 0
        btfsc STATUS, C
        movlw 1
        addwf q2, W
        movwf kk1
        movf kk0, W
        movwf d0
        movf kk1, W
        movwf d1
        clrf d2
        call div24              ; q = b (128..256), r = the remainder (< k)
        decf q0, W
        movwf bm1               ; b - 1 (b = 256: 255)
        movf r0, W
        movwf rr0
        movf r1, W
        movwf rr1
        movf kk0, W
        movwf sl0
        movf kk1, W
        movwf sl1
        movf rr0, W
        movwf rl0
        movf rr1, W
        movwf rl1
        bsf bflags, SLOW
        movlw b'00000101'       ; TMR2ON, 1:4
        movwf tmp
        clrf CCPR1L
        incf bm1, W             ; the first interrupt sets the first Timer2 period's PR2; until then any
        movwf q0
        movlw b'00101100'       ; PWM, duty 2 units of 1 us: the first pulse (the interrupt clears it for the next)
        goto pwm_start
pre4:   movlw b'00000101'       ; TMR2ON, 1:4
        movwf tmp
        clrf CCPR1L
        movlw b'00101100'       ; PWM, DC1B = 10: 2 us
        goto pwm_start
pre1:   movlw b'00000100'       ; TMR2ON, 1:1
        movwf tmp
        movlw 2
        movwf CCPR1L
        movlw b'00001100'       ; PWM, DC1B = 00: 2 us
pwm_start:
        movwf CCP1CON
        decf q0, W              ; PR2 = q - 1
        bsf STATUS, RP0
        movwf PR2
        bcf PIE1, TMR2IE
        btfsc bflags, SLOW
        bsf PIE1, TMR2IE
        bcf STATUS, RP0
        movwf TMR2              ; at PR2: the first increment starts the first pulse
        bcf PIR1, TMR2IF
        btfsc bflags, SLOW
        bsf INTCON, PEIE
        btfsc bflags, BURSTING
        call arm
        movf tmp, W
        movwf T2CON
        bsf flags, FIRING
        return

; Timer0 preloaded with -n mod 256: it overflows on the n-th rising edge, after ceil(n / 256) overflows.
arm:    comf bn0, W
        addlw 1
        movwf TMR0
        movf bn1, W             ; overflows = n >> 8, plus one when n's low byte is not 0
        movwf ovf0
        movf bn2, W
        movwf ovf1
        movf bn0, W
        btfsc STATUS, Z
        goto arm_n
        incf ovf0, F
        btfsc STATUS, Z
        incf ovf1, F
arm_n:  clrf armed
        decf ovf0, W
        iorwf ovf1, W
        btfss STATUS, Z
        goto arm_on
        bsf armed, 1            ; this overflow is the last
        btfss bflags, SLOW
        bsf armed, 0            ; and the interrupt's first instructions stop the train
arm_on: bcf INTCON, T0IF
        bsf INTCON, T0IE
        return

; q2:q1:q0 = (q + n / 2) / n, n = num
div_hz: movf num0, W
        movwf d0
        movf num1, W
        movwf d1
        movf num2, W
        movwf d2
        bcf STATUS, C
        rrf d2, W
        movwf t2
        rrf d1, W
        movwf t1
        rrf d0, W
        addwf q0, F
        movf t1, W
        btfsc STATUS, C
        incfsz t1, W
        addwf q1, F
        movf t2, W
        btfsc STATUS, C
        incfsz t2, W
        addwf q2, F
        goto div24

isr:    movwf w_save
        swapf STATUS, W
        clrf STATUS             ; bank 0
        movwf s_save
        btfss INTCON, T0IF
        goto isr_t2
        btfss INTCON, T0IE
        goto isr_t2
        bcf INTCON, T0IF
        btfsc armed, 1
        goto isr_stop
        movlw 1                 ; an overflow on the way
        subwf ovf0, F
        btfss STATUS, C
        decf ovf1, F
        decf ovf0, W
        iorwf ovf1, W
        btfss STATUS, Z
        goto isr_t2
        bsf armed, 1            ; the next is the last
        btfss bflags, SLOW
        bsf armed, 0
        goto isr_t2
isr_stop:
        clrf CCP1CON            ; RB3 to its latch (a fast train's Timer2 was stopped at the vector)
        clrf T2CON
        clrf armed
        bcf INTCON, T0IE
        bcf INTCON, PEIE
        bsf bflags, DONE
        goto isr_end
isr_t2: btfss bflags, SLOW
        goto isr_end
        btfss PIR1, TMR2IF
        goto isr_end
        bcf PIR1, TMR2IF
        ; a Timer2 period has just begun (TMR2 a few counts in, its PR2 127 or more): its length
        movf bm1, W
        movwf w_tmp
        movf rl0, W
        iorwf rl1, W
        btfsc STATUS, Z
        goto isr_pr2
        incf w_tmp, F           ; a long one
        movlw 1
        subwf rl0, F
        btfss STATUS, C
        decf rl1, F
isr_pr2:
        movf w_tmp, W
        bsf STATUS, RP0
        movwf PR2
        bcf STATUS, RP0
        ; the next period's duty (CCP1 latches it when this one ends): a pulse only after the k-th
        movlw 1
        subwf sl0, F
        btfss STATUS, C
        decf sl1, F
        movf sl0, W
        iorwf sl1, W
        btfss STATUS, Z
        goto isr_quiet
        bsf CCP1CON, 5
        movf kk0, W
        movwf sl0
        movf kk1, W
        movwf sl1
        movf rr0, W
        movwf rl0
        movf rr1, W
        movwf rl1
        goto isr_end
isr_quiet:
        bcf CCP1CON, 5
isr_end:
        swapf s_save, W
        movwf STATUS
        swapf w_save, F
        swapf w_save, W
        retfie

shift_q:                        ; q1:q0 >>= W
        movwf cnt
sq:     bcf STATUS, C
        rrf q1, F
        rrf q0, F
        decfsz cnt, F
        goto sq
        return

; q2:q1:q0 / d2:d1:d0 -> quotient in q, remainder in r
div24:  clrf r0
        clrf r1
        clrf r2
        movlw 24
        movwf cnt
d_loop: bcf STATUS, C
        rlf q0, F
        rlf q1, F
        rlf q2, F
        rlf r0, F
        rlf r1, F
        rlf r2, F
        movf d0, W
        subwf r0, F
        movf d1, W
        btfss STATUS, C
        incfsz d1, W
        subwf r1, F
        movf d2, W
        btfss STATUS, C
        incfsz d2, W
        subwf r2, F
        btfsc STATUS, C
        goto d_set
        movf d0, W
        addwf r0, F
        movf d1, W
        btfsc STATUS, C
        incfsz d1, W
        addwf r1, F
        movf d2, W
        btfsc STATUS, C
        incfsz d2, W
        addwf r2, F
        goto d_next
d_set:  bsf q0, 0
d_next: decfsz cnt, F
        goto d_loop
        return

; ---- sending ----
reply:  call send
line_end:
        movlw 0x0A
        goto tx

send_ram_line:
        call send_ram
        goto line_end

send:   movwf ptr               ; a message from the table, offset in W
s_loop: movf ptr, W
        call msg
        iorlw 0
        btfsc STATUS, Z
        return
        call tx
        incf ptr, F
        goto s_loop

send_ram:                       ; a 0-ended string in RAM at W
        movwf src
sr_loop:
        movf src, W
        movwf FSR
        movf INDF, W
        btfsc STATUS, Z
        return
        call tx
        incf src, F
        goto sr_loop

tx:     movwf txc               ; the 1 ms tick runs on while a reply goes out (12 ms for 12 bytes)
tx_w:   btfsc PIR1, TMR1IF
        call tick
        btfss PIR1, TXIF
        goto tx_w
        movf txc, W
        movwf TXREG
        return

        end
