//! Mock embedded-hal parts that feed an [`St7789Model`] (feature `model`): an [`SpiDevice`]
//! that hands each write to the model together with the DC level *at the time of the write*,
//! the DC [`OutputPin`], and a [`DelayNs`] that advances the model's clock. They share one
//! state through `Rc<RefCell<..>>`, like the wires of a real board.
//!
//! ```
//! use zrow_st7789::mock::MockBus;
//! use zrow_st7789::{St7789Rows, Window};
//! let bus = MockBus::new();
//! let mut rows = St7789Rows::<_, _, 480>::new(bus.spi(), bus.dc(), Window::new(240, 240)).unwrap();
//! rows.init(&mut bus.delay()).unwrap();
//! assert!(bus.model().display_on() && bus.model().errors().is_empty());
//! ```

use crate::model::St7789Model;
use core::cell::{Ref, RefCell, RefMut};
use core::convert::Infallible;
use embedded_hal::delay::DelayNs;
use embedded_hal::digital::{ErrorType as PinErrorType, OutputPin};
use embedded_hal::spi::{self, ErrorType as SpiErrorType, Operation, SpiDevice};
use std::rc::Rc;
use std::vec::Vec;

/// One SPI write as the bus saw it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Write {
    /// The DC level during the write.
    pub dc_high: bool,
    /// Bytes written.
    pub len: usize,
}

#[derive(Debug, Default)]
struct BusState {
    model: St7789Model,
    dc_high: bool,
    log: Vec<Write>,
    fail_spi: bool,
}

/// The shared wires: make the parts from it, read the model through it.
#[derive(Clone, Debug, Default)]
pub struct MockBus(Rc<RefCell<BusState>>);

impl MockBus {
    /// A bus to a freshly powered-on panel.
    pub fn new() -> Self {
        Self::default()
    }
    /// An SPI device on this bus.
    pub fn spi(&self) -> MockSpi {
        MockSpi(self.0.clone())
    }
    /// The DC pin.
    pub fn dc(&self) -> MockDc {
        MockDc(self.0.clone())
    }
    /// A delay that advances the model's clock.
    pub fn delay(&self) -> MockDelay {
        MockDelay(self.0.clone())
    }
    /// The panel model.
    pub fn model(&self) -> Ref<'_, St7789Model> {
        Ref::map(self.0.borrow(), |s| &s.model)
    }
    /// The panel model, to change (e.g. to clear its write counts).
    pub fn model_mut(&self) -> RefMut<'_, St7789Model> {
        RefMut::map(self.0.borrow_mut(), |s| &mut s.model)
    }
    /// Every SPI write so far.
    pub fn writes(&self) -> Vec<Write> {
        self.0.borrow().log.clone()
    }
    /// Forgets the write log.
    pub fn clear_writes(&self) {
        self.0.borrow_mut().log.clear();
    }
    /// Makes every following SPI transaction fail with [`MockSpiError::Injected`] (or work
    /// again).
    pub fn fail_spi(&self, fail: bool) {
        self.0.borrow_mut().fail_spi = fail;
    }
}

/// The mock SPI's errors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MockSpiError {
    /// Failure asked for with [`MockBus::fail_spi`].
    Injected,
    /// A read or transfer: the ST7789 is driven write-only here.
    ReadUnsupported,
}

impl spi::Error for MockSpiError {
    fn kind(&self) -> spi::ErrorKind {
        spi::ErrorKind::Other
    }
}

/// Mock [`SpiDevice`]: writes go to the model with the DC level of the moment.
#[derive(Debug)]
pub struct MockSpi(Rc<RefCell<BusState>>);

impl SpiErrorType for MockSpi {
    type Error = MockSpiError;
}

impl SpiDevice for MockSpi {
    fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), MockSpiError> {
        let mut s = self.0.borrow_mut();
        if s.fail_spi {
            return Err(MockSpiError::Injected);
        }
        for op in operations {
            match op {
                Operation::Write(bytes) => {
                    let dc_high = s.dc_high;
                    s.log.push(Write {
                        dc_high,
                        len: bytes.len(),
                    });
                    s.model.feed(dc_high, bytes);
                }
                Operation::DelayNs(ns) => s.model.advance_ns((*ns).into()),
                _ => return Err(MockSpiError::ReadUnsupported),
            }
        }
        Ok(())
    }
}

/// Mock DC pin.
#[derive(Debug)]
pub struct MockDc(Rc<RefCell<BusState>>);

impl PinErrorType for MockDc {
    type Error = Infallible;
}

impl OutputPin for MockDc {
    fn set_low(&mut self) -> Result<(), Infallible> {
        self.0.borrow_mut().dc_high = false;
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Infallible> {
        self.0.borrow_mut().dc_high = true;
        Ok(())
    }
}

/// Mock delay: advances the model's clock.
#[derive(Debug)]
pub struct MockDelay(Rc<RefCell<BusState>>);

impl DelayNs for MockDelay {
    fn delay_ns(&mut self, ns: u32) {
        self.0.borrow_mut().model.advance_ns(ns.into());
    }
}
